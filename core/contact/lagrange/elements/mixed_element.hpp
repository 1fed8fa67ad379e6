#pragma once
/// @file Residual and tangent of one active mixed energy–momentum NTS contact element
/// (docs/theory.md §4.3.7, (4.9)–(4.10)).
///
/// Unknowns of the element: q_{n+1} = [x_s; y_1 … y_4; d; ξ] ∈ R^20 (layout of invariants.hpp) and
/// λ ∈ R⁶. The building blocks are in invariants.hpp, constraints.hpp and discrete_gradient.hpp.

#include <Eigen/Core>

#include "core/contact/lagrange/constraints.hpp"
#include "core/contact/lagrange/discrete_gradient.hpp"
#include "core/contact/lagrange/invariants.hpp"
#include "core/contact/types.hpp"

namespace stoss::contact {

/// One element's contributions at the current iterate.
/// @note Rq rows 0–14 add to the nodal momentum balance R_x of (4.9) (slave, then master nodes
///       1–4); rows 15–17 are R_d, rows 18–19 R_ξ. Kqq etc. are derivatives with respect to q_{n+1}
///       and λ. λ_1 ≤ 0 in compression.
struct MixedResult {
  Vector20 Rq;     ///< h B_sᵀ ∇̄gᵀ λ, B_s = Dπ(q_m) (4.9)
  Vector6 Rl;      ///< g(π(q_{n+1})) (4.9)
  Matrix20 Kqq;    ///< h [½ Σ_k μ_k A_k + B_sᵀ (Σ_j λ_j ∂∇̄g_j/∂π_b) B⁺_s] (4.10)
  Matrix20x6 Kql;  ///< h B_sᵀ ∇̄gᵀ (4.10)
  Matrix6x20 Klq;  ///< ∇g(π_b) B⁺_s (4.10)
  Vector6 g_n;     ///< g(π(q_n)), for the energy identity ΔH = λ·g(π_n) (4.11)
};

/// The element at (q_n, q_{n+1}) with multipliers λ, gap target f_3 (π7) and step h.
MixedResult mixed_element(const Vector20& q_n, const Vector20& q_1, const Vector6& lambda, double f3,
                          double h);

}  // namespace stoss::contact
