#pragma once
/// @file Invariants of the mixed energy–momentum NTS element and their derivatives
/// (docs/theory.md §4.3.1, §4.3.2, §4.3.4).
///
/// Augmented coordinates q = [x_s; y_1; y_2; y_3; y_4; d; ξ] ∈ R^20 (d at 15–17, ξ at 18–19).
/// With r = x_s − y_1 and e_i = y_i − y_1, the 17 invariants (0-based index k ↔ π_{k+1}) are
/// π1 = r·d, π2–π4 = e_i·d, π5, π6 = ξ, π7 = f_3 (a parameter, not a function of q), π8 = d·d,
/// π9–π11 = e_i·r, π12–π17 = e_i·e_j in the order (2,2),(2,3),(2,4),(3,3),(3,4),(4,4).

#include <Eigen/Core>

#include "core/contact/types.hpp"

namespace stoss::contact {

/// Offsets into q.
struct MixedLayout {
  static constexpr int slave = 0;      ///< x_s
  static constexpr int master = 3;     ///< y_K at 3 + 3K
  static constexpr int director = 15;  ///< d
  static constexpr int xi = 18;        ///< ξ
};

/// q = [x_s; y_1 … y_4; d; ξ].
Vector20 mixed_coordinates(const Eigen::Vector3d& slave, const SegmentNodes& nodes, const Eigen::Vector3d& d,
                           const Eigen::Vector2d& xi);

/// π(q) of table 4.3.2, π7 = f_3.
Vector17 invariants(const Vector20& q, double f3);

/// Dπ = ∂π/∂q (17×20, §4.3.4); the π7 row is zero.
Matrix17x20 invariant_jacobian(const Vector20& q);

/// Σ_k μ_k A_k with A_k = ∂²π_k/∂q² (constant, §4.3.4): the second derivative of μ·π(q).
Matrix20 invariant_hessian_contraction(const Vector17& mu);

}  // namespace stoss::contact
