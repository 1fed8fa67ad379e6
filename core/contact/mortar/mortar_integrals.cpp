#include "core/contact/mortar/mortar_integrals.hpp"

#include <cmath>

namespace stoss::contact::mortar {

const std::array<TrianglePoint, 7>& triangle_rule() {
  // (4.74): Radon's degree-5 rule; a, b = (6 ∓ √15)/21, weights (155 ∓ √15)/1200, centroid 9/40.
  static const std::array<TrianglePoint, 7> rule = [] {
    const double r = std::sqrt(15.0);
    const double a = (6 - r) / 21, b = (6 + r) / 21, wa = (155 - r) / 1200, wb = (155 + r) / 1200;
    return std::array<TrianglePoint, 7>{{{1.0 / 3, 1.0 / 3, 1.0 / 3, 9.0 / 40},
                                         {a, a, 1 - 2 * a, wa},
                                         {a, 1 - 2 * a, a, wa},
                                         {1 - 2 * a, a, a, wa},
                                         {b, b, 1 - 2 * b, wb},
                                         {b, 1 - 2 * b, b, wb},
                                         {1 - 2 * b, b, b, wb}}};
  }();
  return rule;
}

QuadNodes<double> quad_nodes(const SegmentNodes& rows) {
  QuadNodes<double> q;
  for (int K = 0; K < 4; ++K) q[K] = rows.row(K).transpose();
  return q;
}

FacePairIntegrals<double> face_pair_integrals(const SegmentNodes& slave, const SegmentNodes& master,
                                              Multipliers kind) {
  return face_pair_integrals<double>(quad_nodes(slave), quad_nodes(master), kind);
}

Eigen::Matrix<double, 4, 24> weighted_gap_jacobian(const SegmentNodes& slave, const SegmentNodes& master,
                                                   Multipliers kind) {
  using Dual = Eigen::AutoDiffScalar<Eigen::Matrix<double, 24, 1>>;
  QuadNodes<Dual> s, m;
  for (int K = 0; K < 4; ++K)
    for (int i = 0; i < 3; ++i) {
      s[K][i] = Dual(slave(K, i), 24, 3 * K + i);
      m[K][i] = Dual(master(K, i), 24, 12 + 3 * K + i);
    }
  const FacePairIntegrals<Dual> r = face_pair_integrals<Dual>(s, m, kind);
  Eigen::Matrix<double, 4, 24> J;
  for (int j = 0; j < 4; ++j) {
    const Eigen::Matrix<double, 24, 1> d = r.gap[j].derivatives();
    J.row(j) =
        d.size() == 24 ? Eigen::Matrix<double, 1, 24>(d.transpose()) : Eigen::Matrix<double, 1, 24>::Zero();
  }
  return J;
}

}  // namespace stoss::contact::mortar
