#include "core/contact/lagrange/discrete_gradient.hpp"

#include "core/contact/geometry/segment.hpp"
#include "core/contact/lagrange/constraints.hpp"

namespace stoss::contact {
namespace {
// Row k of c_5, c_6 (4.7): −¼ [a0·ΔΠ b2 + a1·Π_m b2 + a1·ΔΠ b1].
double curvature_defect(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Matrix3d& Pi_m,
                        const Eigen::Matrix3d& dPi, const Eigen::Vector3d& b1, const Eigen::Vector3d& b2) {
  return -0.25 * (a0.dot(dPi * b2) + a1.dot(Pi_m * b2) + a1.dot(dPi * b1));  // (4.7)
}
}  // namespace

Vector6 discrete_gradient_defect(const Vector17& pi_m, const Vector17& delta) {
  const InvariantParts m = split_invariants(pi_m), d = split_invariants(delta);
  const BilinearShape s = bilinear_shape(m.xi);
  const Eigen::Vector3d N1 = s.dN.col(0).tail<3>(), N2 = s.dN.col(1).tail<3>(), N12 = s.d2N12.tail<3>();
  const Eigen::Vector3d b1 = N1 * d.xi[0] + N2 * d.xi[1];          // (4.7) t¹ coefficient of N̂
  const Eigen::Vector3d b2 = N12 * d.xi[0] * d.xi[1];              // (4.7) t² coefficient of N̂
  Vector6 c = Vector6::Zero();                                     // (4.7) c_2 = c_3 = c_4 = 0
  c[0] = -0.25 * b2.dot(d.P);                                      // (4.7)
  c[4] = curvature_defect(N1, N12 * d.xi[1], m.Pi, d.Pi, b1, b2);  // (4.7)
  c[5] = curvature_defect(N2, N12 * d.xi[0], m.Pi, d.Pi, b1, b2);  // (4.7)
  return c;
}

DiscreteGradient discrete_gradient(const Vector17& pi_a, const Vector17& pi_b) {
  const Vector17 pi_m = 0.5 * (pi_a + pi_b), delta = pi_b - pi_a;
  const Matrix6x17 G_m = constraint_gradient(pi_m);
  const std::array<Matrix17, 6> H_m = constraint_hessians(pi_m);
  DiscreteGradient dg;
  dg.value = G_m;
  for (int k = 0; k < 6; ++k) dg.derivative[k] = 0.5 * H_m[k];  // (4.8), δ = 0
  const double length = delta.norm();
  if (!(length * length > 0)) return dg;  // (4.6), δ = 0
  const Vector17 unit = delta / length;
  const Vector6 c = discrete_gradient_defect(pi_m, delta);
  const Matrix6x17 G_b = constraint_gradient(pi_b);
  const Matrix17 projector = Matrix17::Identity() - 2 * unit * unit.transpose();
  for (int k = 0; k < 6; ++k) {
    dg.value.row(k) += (c[k] / length) * unit.transpose();  // (4.6): c_k δᵀ/|δ|²
    const Eigen::Matrix<double, 1, 17> dc = G_b.row(k) - G_m.row(k) - 0.5 * (H_m[k] * delta).transpose();
    dg.derivative[k] += unit * dc / length + (c[k] / (length * length)) * projector;  // (4.8)
  }
  return dg;
}

}  // namespace stoss::contact
