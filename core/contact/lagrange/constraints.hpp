#pragma once
/// @file The six constraints of the mixed NTS element as functions of the invariants, with their
/// gradient and Hessians (docs/theory.md §4.3.3, §4.3.5, (4.3)–(4.5)).
///
/// Short names: P = (π2, π3, π4), Q = (π9, π10, π11), Π the symmetric 3×3 matrix stored as
/// (π12 … π17), N̂ = (N_2, N_3, N_4) and its derivatives at ξ = (π5, π6). Indices are 0-based
/// (π_k ↔ entry k − 1).

#include <Eigen/Core>
#include <array>

#include "core/contact/types.hpp"

namespace stoss::contact {

/// The named parts of π.
struct InvariantParts {
  Eigen::Vector3d P;   ///< (π2, π3, π4)
  Eigen::Vector2d xi;  ///< (π5, π6)
  Eigen::Vector3d Q;   ///< (π9, π10, π11)
  Eigen::Matrix3d Pi;  ///< Π_ij = e_{i+1}·e_{j+1}
};
InvariantParts split_invariants(const Vector17& pi);

/// sym(a, b) ∈ R⁶ in Π's storage order: a_i b_j + a_j b_i (i < j), a_i b_i (i = j) (§4.3.5).
Vector6 sym_pairs(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

/// g(π) (4.3): gap − f_3, d ⊥ τ_1, d ⊥ τ_2, ½(|d|² − 1), and the two CPP conditions.
Vector6 constraints(const Vector17& pi);

/// ∇g = ∂g/∂π (6×17) (4.4).
Matrix6x17 constraint_gradient(const Vector17& pi);

/// H_k = ∂²g_k/∂π² (17×17, symmetric) for k = 0…5 (4.5).
std::array<Matrix17, 6> constraint_hessians(const Vector17& pi);

}  // namespace stoss::contact
