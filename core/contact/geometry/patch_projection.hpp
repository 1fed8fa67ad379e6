#pragma once
/// @file Geometry of a tensor patch at ξ and the closest-point projection onto it
/// (docs/smooth_master_surface.md §3.1; formulation §3.2 with the full curvature term of (3.4)).

#include <Eigen/Core>

#include "core/contact/geometry/projection.hpp"
#include "core/contact/geometry/tensor_patch.hpp"

namespace stoss::contact {

/// y(ξ), τ_α, y_{,αβ} and the frame of §3.1 on a patch, positions taken from stacked x.
struct PatchFrame {
  Eigen::Vector2d xi;
  Eigen::Vector3d y, tau1, tau2, y11, y12, y22, normal;
  Eigen::Matrix2d metric, metric_inv;
};
PatchFrame patch_frame(const TensorPatch& p, const Eigen::VectorXd& x, const Eigen::Vector2d& xi);
/// The same from the basis values and second derivatives at ξ, when the caller needs them too.
PatchFrame patch_frame(const TensorPatch& p, const Eigen::VectorXd& x, const Eigen::Vector2d& xi,
                       const BasisValues<double>& b, const BasisCurvatures& c);

/// The CPP of `slave` on patch p: Newton on r_α = (x_s − y)·τ_α with A_αβ = m_αβ − (x_s − y)·y_{,αβ}
/// (3.4), the stop rules of §3.2, then g_N = (x_s − y)·n (3.5). The returned frame carries the
/// geometric fields (y, τ_α, y_{,12}, n, metric); its bilinear shape values are zero.
Projection patch_projection(const Eigen::Vector3d& slave, const TensorPatch& p, const Eigen::VectorXd& x,
                            const Eigen::Vector2d& xi_start = Eigen::Vector2d::Zero());

}  // namespace stoss::contact
