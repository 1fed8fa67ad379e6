#include "core/contact/geometry/projection.hpp"

#include <Eigen/LU>

namespace stoss::contact {
namespace {
Projection finish(const Eigen::Vector3d& slave, const SegmentNodes& nodes, const Eigen::Vector2d& xi,
                  bool converged, int iterations) {
  Projection p;
  p.converged = converged;
  p.xi = xi;
  p.frame = segment_frame(nodes, xi);
  p.gap = (slave - p.frame.y).dot(p.frame.normal);  // (3.5)
  p.iterations = iterations;
  return p;
}

}  // namespace

bool converged_step(double step, int iteration) {
  using L = ProjectionLimits;
  return step < L::step_tolerance ||
         (iteration >= L::stagnation_iterations && step < L::stagnation_tolerance);
}

Eigen::Vector2d projection_residual(const SegmentFrame& frame, const Eigen::Vector3d& r) {
  return {r.dot(frame.tau1), r.dot(frame.tau2)};  // seed eq. 10
}

Eigen::Matrix2d projection_matrix(const SegmentFrame& frame, const Eigen::Vector3d& r) {
  Eigen::Matrix2d A = frame.metric;  // (3.4)
  const double curvature = r.dot(frame.y12);
  A(0, 1) -= curvature;  // (3.4), only A_12 = A_21 has the second term
  A(1, 0) -= curvature;
  return A;
}

Projection closest_point_projection(const Eigen::Vector3d& slave, const SegmentNodes& nodes,
                                    const Eigen::Vector2d& xi_start) {
  using L = ProjectionLimits;
  Eigen::Vector2d xi = xi_start;
  for (int iteration = 1; iteration <= L::max_iterations; ++iteration) {
    const SegmentFrame frame = segment_frame(nodes, xi);
    const Eigen::Vector3d r = slave - frame.y;
    const Eigen::Matrix2d A = projection_matrix(frame, r);
    const double det = A.determinant();
    if (!(det > 0)) return finish(slave, nodes, xi, false, iteration - 1);
    const Eigen::Vector2d step = A.inverse() * projection_residual(frame, r);  // (3.4)
    const Eigen::Vector2d next = xi + step;
    if (!(next.cwiseAbs().maxCoeff() <= L::max_xi)) return finish(slave, nodes, xi, false, iteration);
    xi = next;
    if (converged_step(step.norm(), iteration)) return finish(slave, nodes, xi, true, iteration);
  }
  return finish(slave, nodes, xi, false, L::max_iterations);
}

bool inside(const Eigen::Vector2d& xi, double eps) {
  return xi.cwiseAbs().maxCoeff() <= 1 + eps;
}

}  // namespace stoss::contact
