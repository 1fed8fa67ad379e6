#pragma once
/// @file The NTS Lagrange elements of the midpoint rule (formulation §4.2) and of HHT-α ((2.11)) on a
/// tensor patch (docs/smooth_master_surface.md §3.7): the same forms as midpoint_element.hpp and
/// hht_element.hpp with M master nodes.
///
/// Element vector [x_s; y_0 … y_{M−1}] (3M + 3 entries), on a local copy of the patch whose node K
/// is entry K + 1 of the element's node list (geometry/local_patch.hpp).

#include <Eigen/Core>

#include "core/contact/geometry/local_patch.hpp"
#include "core/contact/geometry/projection.hpp"
#include "core/contact/geometry/tensor_patch.hpp"

namespace stoss::contact {

/// One element's contributions; if a CPP failed (`converged` false) they must not be used.
struct PatchNtsResult {
  bool converged = false;
  Eigen::VectorXd Rx;      ///< h λ N_s (the scheme's weighting)
  double Rl = 0;           ///< g_N(x_{n+1}) − f_3
  Eigen::MatrixXd Kxx;     ///< ∂Rx/∂x_{n+1}
  Eigen::VectorXd Kxl;     ///< ∂Rx/∂λ
  Eigen::RowVectorXd Klx;  ///< N_s(x_{n+1})ᵀ
  Projection end;          ///< CPP of x_{n+1}
};

/// Midpoint (4.2): h λ N_s(x_m), g_N(x_{n+1}) − f_3; both CPPs start from `xi_start`.
PatchNtsResult patch_midpoint_element(const TensorPatch& local, const Eigen::VectorXd& x_n,
                                      const Eigen::VectorXd& x_1, double lambda, double f3, double h,
                                      const Eigen::Vector2d& xi_start);

/// HHT-α (2.11) and generalized-α (2.12): h w λ N_s(x_{n+1}), g_N(x_{n+1}) − f_3, with the weight w of
/// the t_{n+1} forces (1+α; 1−α_f).
PatchNtsResult patch_hht_element(const TensorPatch& local, const Eigen::VectorXd& x_1, double lambda,
                                 double f3, double h, double weight, const Eigen::Vector2d& xi_start);

}  // namespace stoss::contact
