#pragma once
/// @file First variations of the NTS gap at the closest point of a tensor patch, and its Hessian
/// (formulation §3.3, (3.6)–(3.9), with the curvature terms y_{,11}, y_{,22} that a bilinear face
/// lacks; docs/smooth_master_surface.md §3.7). Element vector [x_s; y_0 … y_{M−1}] (3M + 3 entries).

#include <Eigen/Core>
#include <array>

#include "core/contact/geometry/patch_projection.hpp"
#include "core/contact/geometry/tensor_patch.hpp"

namespace stoss::contact {

/// 2 and 3 rows over an element vector of a patch.
using PatchRows2 = Eigen::Matrix<double, 2, Eigen::Dynamic>;
using PatchRows3 = Eigen::Matrix<double, 3, Eigen::Dynamic>;

/// A patch evaluated at ξ: its frame and the basis values and second derivatives the frame is built
/// from, computed once and shared by every variation below.
struct PatchPoint {
  PatchFrame frame;
  Eigen::VectorXd N, dN[2];    ///< N_K, N_{K,α}
  BasisCurvatures curvatures;  ///< N_{K,αβ}
};
PatchPoint patch_point(const TensorPatch& p, const Eigen::VectorXd& x, const Eigen::Vector2d& xi);

/// N_s = ∂g_N/∂x (3.6) and ∂N_s/∂x (3.9) at a converged CPP (ξ, g_N) on patch p, positions from x,
/// with the D_α (3.7) and ∂n/∂x (3.8) they are built from.
struct PatchGapVariations {
  Eigen::VectorXd Ns;   ///< [n; −N_K n]
  Eigen::MatrixXd dNs;  ///< the Hessian of g_N, symmetric up to round-off
  Eigen::MatrixXd D;    ///< ∂ξ^α/∂x as rows α (3.7)
  Eigen::MatrixXd dn;   ///< ∂n/∂x (3.8), 3 rows
};
PatchGapVariations patch_gap_variations(const PatchPoint& at, double gap);
PatchGapVariations patch_gap_variations(const TensorPatch& p, const Eigen::VectorXd& x,
                                        const Eigen::Vector2d& xi, double gap);

/// N_s only.
Eigen::VectorXd patch_gap_gradient(const PatchPoint& at);
Eigen::VectorXd patch_gap_gradient(const TensorPatch& p, const Eigen::VectorXd& x, const Eigen::Vector2d& xi);

/// D_α = ∂ξ^α/∂x = A^{αβ} (T_β + g_N N̄_β) (3.7) only.
Eigen::MatrixXd patch_xi_gradient(const PatchPoint& at, double gap);

/// ∂τ_α/∂x = [0; N_{K,α} 1] + y_{,αβ} ⊗ D_β (3.8), for α = 0, 1 (3 rows each).
std::array<PatchRows3, 2> patch_tangent_gradients(const PatchPoint& at, const Eigen::MatrixXd& D);

/// Σ_α t_α ∂D_α/∂x at fixed covariant t (docs/smooth_master_surface.md §3.8): the derivative of
/// D = A⁻¹ B (3.7) with every curvature term of a patch, which needs the third derivatives of y.
/// `v` holds the variations at the same CPP `at` of patch p (positions x), `dtau` their tangent gradients.
Eigen::MatrixXd patch_contracted_xi_hessian(const TensorPatch& p, const Eigen::VectorXd& x,
                                            const PatchPoint& at, double gap, const PatchGapVariations& v,
                                            const std::array<PatchRows3, 2>& dtau, const Eigen::Vector2d& t);

}  // namespace stoss::contact
