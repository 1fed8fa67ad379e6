#include "core/contact/penalty/patch_penalty_element.hpp"

#include "core/contact/geometry/patch_projection.hpp"
#include "core/contact/geometry/patch_variations.hpp"

namespace stoss::contact {
namespace {

using namespace penalty_law;
constexpr int dynamic = Eigen::Dynamic;

Projection project(const TensorPatch& local, const Eigen::VectorXd& x, const Eigen::Vector2d& xi_start) {
  return patch_projection(x.head<3>(), local, x, xi_start);
}

}  // namespace

PatchPenaltyResult patch_penalty_element(const TensorPatch& local, const Eigen::VectorXd& x_n,
                                         const Eigen::VectorXd& x_1, const FrictionHistory& history,
                                         const PenaltyParameters& p, const Eigen::Vector2d& xi_start,
                                         double face_size) {
  PatchPenaltyResult out(x_1.size());
  const Eigen::VectorXd x_m = 0.5 * (x_n + x_1);
  out.at_n = project(local, x_n, xi_start);  // §5.2 item 1
  out.at_m = project(local, x_m, xi_start);
  out.at_1 = project(local, x_1, xi_start);
  if (!(out.at_n.converged && out.at_m.converged && out.at_1.converged)) return open_result(out, p);

  const PatchGapVariations mid = patch_gap_variations(local, x_m, out.at_m.xi, out.at_m.gap);  // (3.6)–(3.9)
  const Eigen::VectorXd Ns_1 = patch_gap_gradient(local, x_1, out.at_1.xi);                  // (3.6) at x_{n+1}
  const NormalTraction<dynamic> normal =
      normal_traction<dynamic>(p, out.at_n, out.at_m, out.at_1, mid.Ns, Ns_1, face_size);
  if (!(normal.value < 0)) return open_result(out, p);  // open: reset t_T (§5.2 item 7)

  const std::array<PatchRows3, 2> dtau = patch_tangent_gradients(local, x_m, out.at_m.xi, mid.D);  // (3.8)
  const HalfGradients<dynamic> half = half_gradients<dynamic>(out.at_m.frame, dtau);
  const PatchRows2 D_1 = patch_xi_gradient(local, x_1, out.at_1.xi, out.at_1.gap);  // (3.7) at x_{n+1}
  const TangentialKinematics<dynamic> kinematics{out.at_m.frame, half, D_1, out.at_1.xi - out.at_n.xi};
  const TangentialTraction<dynamic> tangential = return_map(kinematics, history.traction, normal, p);  // (5.3)
  const Eigen::MatrixXd xi_hessian =
      tangential.value.isZero(0) ? Eigen::MatrixXd::Zero(x_1.size(), x_1.size())
                                 : patch_contracted_xi_hessian(local, x_m, out.at_m.xi, out.at_m.gap, mid, dtau,
                                                               tangential.value);  // smooth_master_surface §3.8
  const PatchRows2 D_m = mid.D;
  fill_closed_step<dynamic>(out, {mid.Ns, mid.dNs, D_m}, xi_hessian, normal, tangential, p);
  return out;
}

}  // namespace stoss::contact
