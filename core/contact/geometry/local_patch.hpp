#pragma once
/// @file The local numbering every NTS element on a tensor patch uses, Lagrange and penalty alike
/// (docs/smooth_master_surface.md §3.7): element vector [x_s; y_0 … y_{M−1}], the slave node 0 and
/// patch node K entry K + 1 of the element's node list.

#include <Eigen/Core>

#include "core/contact/geometry/tensor_patch.hpp"

namespace stoss::contact {

/// The patch with its nodes renumbered 1 … M (the slave is node 0 of the local element).
TensorPatch local_patch(const TensorPatch& p);

/// [x_s; y_0 … y_{M−1}] from stacked positions x.
Eigen::VectorXd local_positions(int slave, const TensorPatch& p, const Eigen::VectorXd& x);

}  // namespace stoss::contact
