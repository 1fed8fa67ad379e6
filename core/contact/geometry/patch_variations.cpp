#include "core/contact/geometry/patch_variations.hpp"

#include <Eigen/LU>
#include <array>

namespace stoss::contact {
namespace {

/// [a; −c_K a] over the element vector, for node values c.
Eigen::RowVectorXd slave_minus_master(const Eigen::Vector3d& a, const Eigen::VectorXd& c) {
  Eigen::RowVectorXd row(3 + 3 * c.size());
  row.head<3>() = a.transpose();
  for (Eigen::Index K = 0; K < c.size(); ++K) row.segment<3>(3 + 3 * K) = -c[K] * a.transpose();
  return row;
}

/// [0; c_K a] over the element vector.
Eigen::RowVectorXd master_only(const Eigen::Vector3d& a, const Eigen::VectorXd& c) {
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(3 + 3 * c.size());
  for (Eigen::Index K = 0; K < c.size(); ++K) row.segment<3>(3 + 3 * K) = c[K] * a.transpose();
  return row;
}

}  // namespace

Eigen::VectorXd patch_gap_gradient(const TensorPatch& p, const Eigen::VectorXd& x, const Eigen::Vector2d& xi) {
  const PatchFrame f = patch_frame(p, x, xi);
  return slave_minus_master(f.normal, as_vector(patch_values(p, xi[0], xi[1]).N)).transpose();  // (3.6)
}

PatchGapVariations patch_gap_variations(const TensorPatch& p, const Eigen::VectorXd& x, const Eigen::Vector2d& xi,
                                        double gap) {
  const PatchFrame f = patch_frame(p, x, xi);
  const BasisValues<double> b = patch_values(p, xi[0], xi[1]);
  const Eigen::VectorXd N = as_vector(b.N), dN[2] = {as_vector(b.N1), as_vector(b.N2)};
  const Eigen::Vector3d tau[2] = {f.tau1, f.tau2};
  const Eigen::Vector3d y2[2][2] = {{f.y11, f.y12}, {f.y12, f.y22}};  // y_{,αβ}
  const int n = 3 + 3 * p.size();
  Eigen::Matrix2d A = f.metric;  // (3.4) at the CPP, every curvature term
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 2; ++c) A(a, c) -= gap * f.normal.dot(y2[a][c]);
  Eigen::MatrixXd TN(2, n);  // T_β + g_N N̄_β (3.7)
  for (int c = 0; c < 2; ++c) TN.row(c) = slave_minus_master(tau[c], N) + gap * master_only(f.normal, dN[c]);
  const Eigen::MatrixXd D = A.inverse() * TN;  // D_α (3.7)
  Eigen::MatrixXd n_dtau(2, n);                // n·∂τ_α/∂x = [0; N_{K,α} n] + Σ_β (n·y_{,αβ}) D_β (3.8)
  for (int a = 0; a < 2; ++a)
    n_dtau.row(a) = master_only(f.normal, dN[a]) + f.normal.dot(y2[a][0]) * D.row(0) + f.normal.dot(y2[a][1]) * D.row(1);
  Eigen::MatrixXd dn = Eigen::MatrixXd::Zero(3, n);  // ∂n/∂x = −m^{αβ} τ_β ⊗ (n·∂τ_α/∂x) (3.8)
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 2; ++c) dn -= f.metric_inv(a, c) * tau[c] * n_dtau.row(a);
  PatchGapVariations v;
  v.Ns = slave_minus_master(f.normal, N).transpose();  // (3.6)
  v.dNs.resize(n, n);
  v.dNs.topRows<3>() = dn;  // (3.9)
  for (int K = 0; K < p.size(); ++K) {
    const Eigen::RowVectorXd dNK = dN[0][K] * D.row(0) + dN[1][K] * D.row(1);  // ∂N_K/∂x = N_{K,α} D_α
    v.dNs.middleRows<3>(3 + 3 * K) = -f.normal * dNK - N[K] * dn;             // (3.9)
  }
  return v;
}

}  // namespace stoss::contact
