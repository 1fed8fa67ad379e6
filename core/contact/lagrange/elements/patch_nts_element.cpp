#include "core/contact/lagrange/elements/patch_nts_element.hpp"

#include "core/contact/geometry/patch_projection.hpp"
#include "core/contact/geometry/patch_variations.hpp"

namespace stoss::contact {
namespace {
Projection project(const TensorPatch& local, const Eigen::VectorXd& x, const Eigen::Vector2d& xi_start) {
  return patch_projection(x.head<3>(), local, x, xi_start);
}
}  // namespace

PatchNtsResult patch_midpoint_element(const TensorPatch& local, const Eigen::VectorXd& x_n,
                                      const Eigen::VectorXd& x_1, double lambda, double f3, double h,
                                      const Eigen::Vector2d& xi_start) {
  const Eigen::VectorXd x_m = 0.5 * (x_n + x_1);
  const Projection mid = project(local, x_m, xi_start);
  PatchNtsResult out;
  out.end = project(local, x_1, xi_start);
  out.converged = mid.converged && out.end.converged;
  const PatchGapVariations v = patch_gap_variations(local, x_m, mid.xi, mid.gap);
  out.Rx = h * lambda * v.Ns;                                        // (4.2)
  out.Rl = out.end.gap - f3;                                         // (4.2)
  out.Kxx = 0.5 * h * lambda * v.dNs;                                // (4.2), (3.9)
  out.Kxl = h * v.Ns;                                                // (4.2)
  out.Klx = patch_gap_gradient(local, x_1, out.end.xi).transpose();  // (3.6)
  return out;
}

PatchNtsResult patch_hht_element(const TensorPatch& local, const Eigen::VectorXd& x_1, double lambda,
                                 double f3, double h, double weight, const Eigen::Vector2d& xi_start) {
  PatchNtsResult out;
  out.end = project(local, x_1, xi_start);
  out.converged = out.end.converged;
  const PatchGapVariations v = patch_gap_variations(local, x_1, out.end.xi, out.end.gap);
  const double step_weight = h * weight;  // (2.11), (2.12): w on the t_{n+1} forces
  out.Rx = step_weight * lambda * v.Ns;
  out.Rl = out.end.gap - f3;
  out.Kxx = step_weight * lambda * v.dNs;  // (3.9)
  out.Kxl = step_weight * v.Ns;
  out.Klx = v.Ns.transpose();
  return out;
}

}  // namespace stoss::contact
