#pragma once
/// @file The mixed energy–momentum NTS element on a tensor patch with M master nodes
/// (docs/smooth_master_surface.md §3; the structure of formulation §4.3 with more master nodes).
///
/// With the generators u_0 = r = x_s − y_0, u_i = e_i = y_i − y_0 (i = 1 … M−1), u_M = d, the six
/// constraints are linear in their Gram matrix G = U Uᵀ: g_k = ⟨S_k(ξ), G⟩ + κ_k (3.2), with
/// symmetric coefficient matrices S_k built from N̂, N̂_{,α}. The discrete gradient splits the
/// product (3.3): ∇̄_G g_k = ½(S_k(ξ_n) + S_k(ξ_{n+1})), ∇̄_ξ g_k = ⟨Ḡ, ∇̄_α S_k⟩ with the symmetrised
/// coordinate divided differences ∇̄_α S_k (3.4), exact in closed form; g(π_{n+1}) − g(π_n) = ∇̄g·Δπ
/// holds to round-off, so (4.11) holds. Both momenta follow from the invariance of G.
///
/// Element vector: [x_s; y_0 … y_{M−1}; d; ξ] (3M + 8 entries), then λ ∈ R⁶.

#include <Eigen/Core>

#include "core/contact/geometry/tensor_patch.hpp"
#include "core/contact/types.hpp"

namespace stoss::contact {

/// Positions and mixed coordinates of one element at one time.
struct PatchMixedState {
  Eigen::Vector3d slave;
  Eigen::MatrixXd master;  ///< M × 3, rows in the patch's node order
  Eigen::Vector3d d;
  Eigen::Vector2d xi;
};

/// One element's contributions at the current iterate.
/// @note Rq rows: slave, the M master nodes, then R_d (3) and R_ξ (2). K is the full element block
///       [∂Rq/∂q, ∂Rq/∂λ; ∂Rλ/∂q, 0] with respect to (q_{n+1}, λ).
struct PatchMixedResult {
  Eigen::VectorXd Rq;  ///< h (force of (4.9) on x, d, ξ)
  Vector6 Rl;          ///< g(π_{n+1})
  Eigen::MatrixXd K;   ///< (3M + 14)²
  Vector6 g_n;         ///< g(π_n), for ΔH = λ·g(π_n) (4.11)
};

/// g(π) of the element state s with gap target f_3 (3.2).
Vector6 patch_constraints(const TensorPatch& p, const PatchMixedState& s, double f3);

/// The element at (state at t_n, state at t_{n+1}) with multipliers λ, gap target f_3 and step h.
PatchMixedResult patch_mixed_element(const TensorPatch& p, const PatchMixedState& at_n,
                                     const PatchMixedState& at_1, const Vector6& lambda, double f3, double h);

}  // namespace stoss::contact
