#pragma once
/// @file The part of a step's increment that no rigid motion explains, with its derivative
/// (docs/smooth_master_surface.md §3.9): the direction in which the penalty element corrects its
/// midpoint gradients into discrete gradients without moving the element's momenta.

#include <Eigen/Core>

namespace stoss::contact {

/// q = P d for d = x_{n+1} − x_n over an element (3 entries per node), P the orthogonal projection
/// onto the complement of the element's rigid motions at x_m = (x_n + x_{n+1})/2: translations t and
/// rotations ω × x_m,node. Σ_nodes q = 0 and Σ x_m × q = 0.
struct RigidFreeIncrement {
  Eigen::VectorXd q;         ///< P d
  double size = 0;           ///< s = d·q = |q|²
  Eigen::MatrixXd dq;        ///< ∂q/∂x_{n+1} (x_n fixed)
  Eigen::RowVectorXd dsize;  ///< ∂s/∂x_{n+1}
};

RigidFreeIncrement rigid_free_increment(const Eigen::VectorXd& x_n, const Eigen::VectorXd& x_1);

}  // namespace stoss::contact
