#include "core/contact/geometry/segment.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

namespace stoss::contact {
namespace {
constexpr double corner_xi1[4] = {-1, 1, 1, -1};
constexpr double corner_xi2[4] = {-1, -1, 1, 1};

Eigen::Matrix2d inverse_or_zero(const Eigen::Matrix2d& m) {
  return m.determinant() > 0 ? Eigen::Matrix2d(m.inverse()) : Eigen::Matrix2d::Zero();
}

Eigen::Vector3d unit_or_zero(const Eigen::Vector3d& v) {
  const double length = v.norm();
  return length > 0 ? Eigen::Vector3d(v / length) : Eigen::Vector3d::Zero();
}
}  // namespace

BilinearShape bilinear_shape(const Eigen::Vector2d& xi) {
  BilinearShape s;
  for (int K = 0; K < 4; ++K) {
    const double a = 1 + xi[0] * corner_xi1[K], b = 1 + xi[1] * corner_xi2[K];
    s.N[K] = 0.25 * a * b;                              // (3.1)
    s.dN(K, 0) = 0.25 * corner_xi1[K] * b;              // (3.1)
    s.dN(K, 1) = 0.25 * corner_xi2[K] * a;              // (3.1)
    s.d2N12[K] = 0.25 * corner_xi1[K] * corner_xi2[K];  // (3.1)
  }
  return s;
}

SegmentFrame segment_frame(const SegmentNodes& nodes, const Eigen::Vector2d& xi) {
  const BilinearShape s = bilinear_shape(xi);
  SegmentFrame f;
  f.xi = xi;
  f.N = s.N;
  f.dN = s.dN;
  f.d2N12 = s.d2N12;
  f.y = nodes.transpose() * s.N;                                                               // (3.2)
  f.tau1 = nodes.transpose() * s.dN.col(0);                                                    // (3.2)
  f.tau2 = nodes.transpose() * s.dN.col(1);                                                    // (3.2)
  f.y12 = nodes.transpose() * s.d2N12;                                                         // (3.2)
  f.metric << f.tau1.dot(f.tau1), f.tau1.dot(f.tau2), f.tau2.dot(f.tau1), f.tau2.dot(f.tau2);  // (3.3)
  f.metric_inv = inverse_or_zero(f.metric);                                                    // (3.3)
  f.normal = unit_or_zero(f.tau1.cross(f.tau2));                                               // (3.3)
  return f;
}

}  // namespace stoss::contact
