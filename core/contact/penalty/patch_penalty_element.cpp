#include "core/contact/penalty/patch_penalty_element.hpp"

#include "core/contact/geometry/patch_projection.hpp"
#include "core/contact/geometry/patch_variations.hpp"
#include "core/contact/penalty/rigid_free_increment.hpp"

namespace stoss::contact {
namespace {

using namespace penalty_law;
constexpr int dynamic = Eigen::Dynamic;

/// |q|² ≤ this × |d|²: the increment is rigid to round-off and the midpoint gradients stand (§3.9).
constexpr double rigid_increment = 1e-16;

Projection project(const TensorPatch& local, const Eigen::VectorXd& x, const Eigen::Vector2d& xi_start) {
  return patch_projection(x.head<3>(), local, x, xi_start);
}

/// The discrete gradients ∇̄g_N, ∇̄ξ^α of a closed step and the tangent of their correction
/// (docs/smooth_master_surface.md (3.9)): ∇̄f = ∇f(x_m) + c_f q with c_f = (Δf − ∇f(x_m)·d)/(d·q), so
/// that ∇̄f·d = Δf exactly and q (rigid_free_increment.hpp) adds no net force or torque.
struct DiscreteGradients {
  Eigen::VectorXd Ns;                  ///< ∇̄g_N
  PatchRows2 D;                        ///< ∇̄ξ^α as rows
  Eigen::MatrixXd correction_tangent;  ///< ∂(C q)/∂x_{n+1} at fixed tractions, C = t_N c_g + t_α c_ξ^α
};

/// What the correction needs of the step: the CPPs at both ends, the gradients at x_m and x_{n+1}
/// and the tractions' Hessian terms ½ H d (t_N ∇²g_N and Σ t_α ∇²ξ^α at x_m).
struct StepGradients {
  const Projection &at_n, &at_1;
  const PatchGapVariations& mid;
  const PatchRows2& D_m;
  const Eigen::VectorXd& Ns_1;
  const PatchRows2& D_1;
  const Eigen::MatrixXd& xi_hessian;
};

DiscreteGradients discrete_gradients(const StepGradients& s, const Eigen::VectorXd& x_n,
                                     const Eigen::VectorXd& x_1, double t_N, const Eigen::Vector2d& t) {
  const Eigen::Index n = x_1.size();
  DiscreteGradients out{s.mid.Ns, s.D_m, Eigen::MatrixXd::Zero(n, n)};
  const Eigen::VectorXd d = x_1 - x_n;
  const RigidFreeIncrement r = rigid_free_increment(x_n, x_1);
  if (!(r.size > rigid_increment * d.squaredNorm())) return out;
  const double c_g = (s.at_1.gap - s.at_n.gap - s.mid.Ns.dot(d)) / r.size;    // (3.9)
  const Eigen::Vector2d c_xi = (s.at_1.xi - s.at_n.xi - s.D_m * d) / r.size;  // (3.9)
  out.Ns += c_g * r.q;
  out.D += c_xi * r.q.transpose();
  const double C = t_N * c_g + t.dot(c_xi);
  const Eigen::VectorXd dmismatch = t_N * (s.Ns_1 - s.mid.Ns - 0.5 * s.mid.dNs.transpose() * d) +
                                    (s.D_1 - s.D_m).transpose() * t - 0.5 * s.xi_hessian.transpose() * d;
  const Eigen::RowVectorXd dC = (dmismatch.transpose() - C * r.dsize) / r.size;
  out.correction_tangent = r.q * dC + C * r.dq;
  return out;
}

}  // namespace

PatchPenaltyResult patch_penalty_element(const TensorPatch& local, const Eigen::VectorXd& x_n,
                                         const Eigen::VectorXd& x_1, const FrictionHistory& history,
                                         const PenaltyParameters& p, const Eigen::Vector2d& xi_start,
                                         double face_size) {
  PatchPenaltyResult out(x_1.size());
  const Eigen::VectorXd x_m = p.at_end ? x_1 : Eigen::VectorXd(0.5 * (x_n + x_1));  // §5b.6: x_{n+1} static
  out.at_n = project(local, x_n, xi_start);                                         // §5.2 item 1
  out.at_1 = project(local, x_1, xi_start);
  out.at_m = p.at_end ? out.at_1 : project(local, x_m, xi_start);
  if (!(out.at_n.converged && out.at_m.converged && out.at_1.converged)) return open_result(out, p);

  const PatchPoint mid_point = patch_point(local, x_m, out.at_m.xi),
                   end_point = patch_point(local, x_1, out.at_1.xi);
  const PatchGapVariations mid = patch_gap_variations(mid_point, out.at_m.gap);  // (3.6)–(3.9)
  const Eigen::VectorXd Ns_1 = patch_gap_gradient(end_point);                    // (3.6) at x_{n+1}
  const NormalTraction<dynamic> normal =
      normal_traction<dynamic>(p, out.at_n, out.at_m, out.at_1, mid.Ns, Ns_1, face_size);
  if (!(normal.value < 0)) return open_result(out, p);  // open: reset t_T (§5.2 item 7)

  const std::array<PatchRows3, 2> dtau = patch_tangent_gradients(mid_point, mid.D);  // (3.8)
  const double theta = evaluation_weight(p);
  const PointGradients<dynamic> at_point = point_gradients<dynamic>(out.at_m.frame, dtau, theta);
  const PatchRows2 D_1 = patch_xi_gradient(end_point, out.at_1.gap);  // (3.7) at x_{n+1}
  const TangentialKinematics<dynamic> kinematics{out.at_m.frame, at_point, D_1, out.at_1.xi - out.at_n.xi};
  const TangentialTraction<dynamic> tangential =
      return_map(kinematics, history.traction, normal, p);  // (5.3)
  const Eigen::MatrixXd xi_hessian =
      tangential.value.isZero(0)
          ? Eigen::MatrixXd::Zero(x_1.size(), x_1.size())
          : patch_contracted_xi_hessian(local, x_m, mid_point, out.at_m.gap, mid, dtau,
                                        tangential.value);  // smooth_master_surface §3.8
  const PatchRows2 D_m = mid.D;
  // Static steps take the gradients at x_{n+1} as they are: no step to be exact over (§5b.6).
  const DiscreteGradients bar =
      p.at_end ? DiscreteGradients{mid.Ns, D_m, Eigen::MatrixXd::Zero(x_1.size(), x_1.size())}
               : discrete_gradients({out.at_n, out.at_1, mid, D_m, Ns_1, D_1, xi_hessian}, x_n, x_1,
                                    normal.value, tangential.value);
  fill_closed_step<dynamic>(out, {bar.Ns, mid.dNs, bar.D, theta}, xi_hessian, normal, tangential,
                            p);  // (5.2) with (3.9)
  out.tangent += bar.correction_tangent;
  return out;
}

}  // namespace stoss::contact
