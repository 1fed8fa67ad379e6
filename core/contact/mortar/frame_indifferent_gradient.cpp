#include "core/contact/mortar/frame_indifferent_gradient.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <array>

namespace stoss::contact::mortar {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

/// A step whose deformation part is below this fraction of the face size counts as rigid (4.87): its gap
/// increments are round-off, and the correction along w would be round-off divided by |w|².
constexpr double rigid_step = 1e-10;

Vector3d node(const Vector24& x, int a) {
  return x.segment<3>(3 * a);
}

}  // namespace

StepDeformation step_deformation(const Vector24& x_n, const Vector24& x_1) {
  const Vector24 delta = x_1 - x_n, mid = 0.5 * (x_n + x_1);
  Vector3d centre = Vector3d::Zero(), mean_step = Vector3d::Zero();
  for (int a = 0; a < 8; ++a) centre += node(mid, a) / 8, mean_step += node(delta, a) / 8;
  std::array<Vector3d, 8> r, d;
  Vector3d moment = Vector3d::Zero();   // L = Σ r_a × Δ_a
  Matrix3d inertia = Matrix3d::Zero();  // J = Σ |r_a|² I − r_a r_aᵀ
  for (int a = 0; a < 8; ++a) {
    r[a] = node(mid, a) - centre, d[a] = node(delta, a) - mean_step;
    moment += r[a].cross(node(delta, a));
    inertia += r[a].squaredNorm() * Matrix3d::Identity() - r[a] * r[a].transpose();
  }
  const Eigen::PartialPivLU<Matrix3d> lu(inertia);
  const Vector3d omega = lu.solve(moment);  // (4.85)
  StepDeformation out;
  for (int a = 0; a < 8; ++a) out.w.segment<3>(3 * a) = d[a] - omega.cross(r[a]);
  // (4.86): ∂/∂x_{n+1} along e at node b moves Δ_b by e, every r_a by ½(δ_ab − 1/8) e.
  for (int b = 0; b < 8; ++b)
    for (int i = 0; i < 3; ++i) {
      const Vector3d e = Vector3d::Unit(i);
      const Vector3d d_moment = 0.5 * e.cross(d[b]) + r[b].cross(e);
      const Matrix3d d_inertia =
          r[b].dot(e) * Matrix3d::Identity() - 0.5 * (e * r[b].transpose() + r[b] * e.transpose());
      const Vector3d d_omega = lu.solve(d_moment - d_inertia * omega);
      for (int a = 0; a < 8; ++a) {
        const double share = (a == b ? 1.0 : 0.0) - 1.0 / 8;
        out.derivative.block<3, 1>(3 * a, 3 * b + i) =
            share * e - d_omega.cross(r[a]) - 0.5 * share * omega.cross(e);
      }
    }
  return out;
}

PairDiscreteGradient discrete_gradient(const PairStep& step, const Eigen::Vector4d& lambda) {
  PairDiscreteGradient out;
  out.gradient = step.at_midpoint.gradient;
  if (step.weighted_hessian) out.tangent = 0.5 * *step.weighted_hessian;
  const StepDeformation deformation = step_deformation(step.x_n, step.x_1);
  const Vector24& w = deformation.w;
  const double ww = w.squaredNorm();
  if (!(ww > rigid_step * rigid_step * step.length * step.length)) return out;
  const Vector24 delta = step.x_1 - step.x_n;
  // c_j = (g̃_j(x_{n+1}) − g̃_j(x_n) − ∂g̃_j/∂x(x_m)·Δ) / |w|²,  G_j = ∂g̃_j/∂x(x_m) + c_j wᵀ    (4.87)
  const Eigen::Vector4d c = (step.at_end.gap - step.gap_n - step.at_midpoint.gradient * delta) / ww;
  out.gradient += c * w.transpose();
  if (!step.weighted_hessian) return out;
  // (4.88): Σ_j λ_j G_j = ∇φ(x_m) + C w with φ = Σ_j λ_j g̃_j, C = Σ_j λ_j c_j.
  const double C = lambda.dot(c);
  const Matrix24& H = *step.weighted_hessian;
  const Eigen::Matrix<double, 1, 24> grad_end = lambda.transpose() * step.at_end.gradient;
  const Eigen::Matrix<double, 1, 24> grad_mid = lambda.transpose() * step.at_midpoint.gradient;
  const Eigen::Matrix<double, 1, 24> w_dw = w.transpose() * deformation.derivative;
  const Eigen::Matrix<double, 1, 24> dC =
      (grad_end - grad_mid - 0.5 * (H * delta).transpose() - 2 * C * w_dw) / ww;
  out.tangent += w * dC + C * deformation.derivative;
  return out;
}

}  // namespace stoss::contact::mortar
