#pragma once
/// @file First variations of the NTS gap at the closest point of a tensor patch, and its Hessian
/// (formulation §3.3, (3.6)–(3.9), with the curvature terms y_{,11}, y_{,22} that a bilinear face
/// lacks; docs/smooth_master_surface.md §3.7). Element vector [x_s; y_0 … y_{M−1}] (3M + 3 entries).

#include <Eigen/Core>

#include "core/contact/geometry/patch_projection.hpp"
#include "core/contact/geometry/tensor_patch.hpp"

namespace stoss::contact {

/// N_s = ∂g_N/∂x (3.6) and ∂N_s/∂x (3.9) at a converged CPP (ξ, g_N) on patch p, positions from x.
struct PatchGapVariations {
  Eigen::VectorXd Ns;   ///< [n; −N_K n]
  Eigen::MatrixXd dNs;  ///< the Hessian of g_N, symmetric up to round-off
};
PatchGapVariations patch_gap_variations(const TensorPatch& p, const Eigen::VectorXd& x, const Eigen::Vector2d& xi,
                                        double gap);

/// N_s only.
Eigen::VectorXd patch_gap_gradient(const TensorPatch& p, const Eigen::VectorXd& x, const Eigen::Vector2d& xi);

}  // namespace stoss::contact
