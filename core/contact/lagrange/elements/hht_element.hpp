#pragma once
/// @file Residual and tangent of one active NTS Lagrange element of the HHT-α scheme
/// (docs/theory.md §2.4, (2.11), with the NTS gap of §3).

#include <Eigen/Core>

#include "core/contact/geometry/projection.hpp"
#include "core/contact/types.hpp"

namespace stoss::contact {

/// One element's contributions at the current iterate; element vectors are [x_s; y_1 … y_4].
/// @note Only the t_{n+1} part of (2.11): the t_n part −α h λ_n N_s(x_n) does not depend on the
///       unknowns and is added by NtsContactTerm from the last converged step (`hht_element_force`).
///       If the CPP failed (`converged` false) the blocks must not be used.
struct HhtElementResult {
  bool converged = false;  ///< the CPP at x_{n+1} converged
  Vector15 Rx;             ///< h (1+α) λ N_s(x_{n+1}) (2.11), (3.6)
  double Rl = 0;           ///< g_N(x_{n+1}) − f_3 (2.11): the constraint at t_{n+1}
  Matrix15 Kxx;            ///< h (1+α) λ ∂N_s/∂x(x_{n+1}) (3.9)
  Vector15 Kxl;            ///< h (1+α) N_s(x_{n+1})
  RowVector15 Klx;         ///< N_s(x_{n+1})ᵀ
  Projection end;          ///< CPP of x_{n+1}
};

/// The element at x_{n+1} with multiplier λ_{n+1}, gap target f_3, step h and the weight w of the
/// t_{n+1} forces (HHT-α: 1+α (2.11); generalized-α: 1−α_f (2.12)); the CPP starts from `xi_start`.
HhtElementResult hht_element(const Vector15& x_1, double lambda, double f3, double h, double weight,
                             const Eigen::Vector2d& xi_start);

/// λ N_s(x) (3.6): the element's contact force at a converged configuration x (no h, no α weight); zero
/// if the CPP fails.
Vector15 hht_element_force(const Vector15& x, double lambda, const Eigen::Vector2d& xi_start);

}  // namespace stoss::contact
