#include "core/contact/geometry/variations.hpp"

#include <Eigen/LU>

#include "core/contact/geometry/projection.hpp"

namespace stoss::contact {

Vector15 gap_gradient(const SegmentFrame& frame) {
  Vector15 Ns;
  Ns.head<3>() = frame.normal;                                                        // (3.6)
  for (int K = 0; K < 4; ++K) Ns.segment<3>(3 + 3 * K) = -frame.N[K] * frame.normal;  // (3.6)
  return Ns;
}

Matrix2x15 tangent_variation(const SegmentFrame& frame) {
  Matrix2x15 T;
  for (int a = 0; a < 2; ++a) {
    T.block<1, 3>(a, 0) = frame.tau(a).transpose();  // (3.7)
    for (int K = 0; K < 4; ++K) T.block<1, 3>(a, 3 + 3 * K) = -frame.N[K] * frame.tau(a).transpose();
  }
  return T;
}

Matrix2x15 normal_variation(const SegmentFrame& frame) {
  Matrix2x15 Nbar = Matrix2x15::Zero();
  for (int a = 0; a < 2; ++a)
    for (int K = 0; K < 4; ++K)
      Nbar.block<1, 3>(a, 3 + 3 * K) = frame.dN(K, a) * frame.normal.transpose();  // (3.7)
  return Nbar;
}

Matrix2x15 xi_gradient(const SegmentFrame& frame, double gap) {
  const Eigen::Matrix2d A = projection_matrix(frame, gap * frame.normal);           // (3.4) at the CPP
  return A.inverse() * (tangent_variation(frame) + gap * normal_variation(frame));  // (3.7)
}

std::array<Matrix3x15, 2> tangent_gradients(const SegmentFrame& frame, const Matrix2x15& D) {
  std::array<Matrix3x15, 2> dtau;
  for (int a = 0; a < 2; ++a) {
    dtau[a] = frame.y12 * D.row(1 - a);  // (3.8): y_{,12} ⊗ D_β, β ≠ α
    for (int K = 0; K < 4; ++K)
      dtau[a].block<3, 3>(0, 3 + 3 * K).diagonal().array() += frame.dN(K, a);  // (3.8)
  }
  return dtau;
}

Matrix3x15 normal_gradient(const SegmentFrame& frame, const std::array<Matrix3x15, 2>& dtau) {
  Matrix3x15 dn = Matrix3x15::Zero();
  for (int a = 0; a < 2; ++a) {
    const RowVector15 n_dtau = frame.normal.transpose() * dtau[a];
    for (int b = 0; b < 2; ++b) dn -= frame.metric_inv(a, b) * frame.tau(b) * n_dtau;  // (3.8)
  }
  return dn;
}

Matrix15 gap_hessian(const SegmentFrame& frame, const Matrix2x15& D, const Matrix3x15& dn) {
  Matrix15 dNs;
  dNs.topRows<3>() = dn;  // (3.9)
  for (int K = 0; K < 4; ++K) {
    const RowVector15 dNK = frame.dN.row(K) * D;                           // ∂N_K/∂x = N_{K,α} D_α
    dNs.middleRows<3>(3 + 3 * K) = -frame.normal * dNK - frame.N[K] * dn;  // (3.9)
  }
  return dNs;
}

GapVariations gap_variations(const SegmentFrame& frame, double gap) {
  GapVariations v;
  v.Ns = gap_gradient(frame);
  v.D = xi_gradient(frame, gap);
  v.dtau = tangent_gradients(frame, v.D);
  v.dn = normal_gradient(frame, v.dtau);
  v.dNs = gap_hessian(frame, v.D, v.dn);
  return v;
}

}  // namespace stoss::contact
