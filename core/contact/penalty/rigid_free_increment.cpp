#include "core/contact/penalty/rigid_free_increment.hpp"

#include <Eigen/Cholesky>

namespace stoss::contact {
namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d S;
  S << 0, -a[2], a[1], a[2], 0, -a[0], -a[1], a[0], 0;
  return S;
}

/// R (n × 6): per node [1 | −skew(x_m,node)], the translations and the rotations ω × x_m,node.
Eigen::MatrixXd rigid_modes(const Eigen::VectorXd& x_m) {
  Eigen::MatrixXd R(x_m.size(), 6);
  for (Eigen::Index i = 0; i < x_m.size(); i += 3) {
    R.block<3, 3>(i, 0).setIdentity();
    R.block<3, 3>(i, 3) = -skew(x_m.segment<3>(i));  // ω × x = −x × ω
  }
  return R;
}

/// The matrix of δ ↦ [0; Σ_nodes δ_node × v_node], the rotation rows of (∂R/∂x_m [δ])ᵀ v.
Eigen::MatrixXd transposed_mode_derivative(const Eigen::VectorXd& v) {
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(6, v.size());
  for (Eigen::Index i = 0; i < v.size(); i += 3) M.block<3, 3>(3, i) = -skew(v.segment<3>(i));
  return M;
}

}  // namespace

RigidFreeIncrement rigid_free_increment(const Eigen::VectorXd& x_n, const Eigen::VectorXd& x_1) {
  const Eigen::VectorXd d = x_1 - x_n, x_m = 0.5 * (x_n + x_1);
  const Eigen::Index n = d.size();
  const Eigen::MatrixXd R = rigid_modes(x_m);
  const Eigen::LDLT<Eigen::MatrixXd> G(R.transpose() * R);  // G = RᵀR
  const Eigen::VectorXd u = G.solve(R.transpose() * d);     // (t, ω) of the rigid part of d
  RigidFreeIncrement out;
  const Eigen::VectorXd rigid = R * u;
  out.q = d - rigid;
  out.size = d.dot(out.q);
  // ∂(R u)/∂x_m at fixed u: ω × δ per node; ∂u/∂x_m = G⁻¹[(∂R)ᵀ d − (∂R)ᵀ R u − Rᵀ (∂R) u].
  Eigen::MatrixXd omega_cross = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; i += 3) omega_cross.block<3, 3>(i, i) = skew(u.tail<3>());
  const Eigen::MatrixXd du_dxm = G.solve(transposed_mode_derivative(d) - transposed_mode_derivative(rigid) -
                                         R.transpose() * omega_cross);
  const Eigen::MatrixXd dq_dxm = -omega_cross - R * du_dxm;
  out.dq = Eigen::MatrixXd::Identity(n, n) - R * G.solve(R.transpose()) + 0.5 * dq_dxm;  // P + ½ ∂(Pd)/∂x_m
  out.dsize = out.q.transpose() + d.transpose() * out.dq;                                // s = d·q
  return out;
}

}  // namespace stoss::contact
