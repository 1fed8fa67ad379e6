#include "core/contact/geometry/patch_projection.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

namespace stoss::contact {
namespace {

SegmentFrame as_segment_frame(const PatchFrame& f) {
  SegmentFrame s;
  s.xi = f.xi;
  s.y = f.y;
  s.tau1 = f.tau1;
  s.tau2 = f.tau2;
  s.y12 = f.y12;
  s.normal = f.normal;
  s.metric = f.metric;
  s.metric_inv = f.metric_inv;
  s.N.setZero();
  s.dN.setZero();
  s.d2N12.setZero();
  return s;
}

Projection finish(const Eigen::Vector3d& slave, const PatchFrame& f, bool converged, int iterations) {
  Projection p;
  p.converged = converged;
  p.xi = f.xi;
  p.frame = as_segment_frame(f);
  p.gap = (slave - f.y).dot(f.normal);  // (3.5)
  p.iterations = iterations;
  return p;
}
}  // namespace

PatchFrame patch_frame(const TensorPatch& p, const Eigen::VectorXd& x, const Eigen::Vector2d& xi) {
  return patch_frame(p, x, xi, patch_values(p, xi[0], xi[1]), patch_curvatures(p, xi));
}

PatchFrame patch_frame(const TensorPatch& p, const Eigen::VectorXd& x, const Eigen::Vector2d& xi,
                       const BasisValues<double>& b, const BasisCurvatures& c) {
  PatchFrame f;
  f.xi = xi;
  f.y = combine_nodes(p, as_vector(b.N), x);  // (2.3)
  f.tau1 = combine_nodes(p, as_vector(b.N1), x);
  f.tau2 = combine_nodes(p, as_vector(b.N2), x);
  f.y11 = combine_nodes(p, c.N11, x);
  f.y12 = combine_nodes(p, c.N12, x);
  f.y22 = combine_nodes(p, c.N22, x);
  f.metric << f.tau1.dot(f.tau1), f.tau1.dot(f.tau2), f.tau2.dot(f.tau1), f.tau2.dot(f.tau2);  // (3.3)
  f.metric_inv = f.metric.determinant() > 0 ? Eigen::Matrix2d(f.metric.inverse()) : Eigen::Matrix2d::Zero();
  const Eigen::Vector3d n = f.tau1.cross(f.tau2);
  f.normal = n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Zero();  // (3.3)
  return f;
}

Projection patch_projection(const Eigen::Vector3d& slave, const TensorPatch& p, const Eigen::VectorXd& x,
                            const Eigen::Vector2d& xi_start) {
  using L = ProjectionLimits;
  PatchFrame f = patch_frame(p, x, xi_start);
  for (int iteration = 1; iteration <= L::max_iterations; ++iteration) {
    const Eigen::Vector3d r = slave - f.y;
    Eigen::Matrix2d A = f.metric;  // (3.4) with every curvature term
    A(0, 0) -= r.dot(f.y11);
    A(0, 1) -= r.dot(f.y12);
    A(1, 0) -= r.dot(f.y12);
    A(1, 1) -= r.dot(f.y22);
    if (!(A.determinant() > 0)) return finish(slave, f, false, iteration - 1);
    const Eigen::Vector2d step = A.inverse() * Eigen::Vector2d(r.dot(f.tau1), r.dot(f.tau2));  // (3.4)
    const Eigen::Vector2d next = f.xi + step;
    if (!(next.cwiseAbs().maxCoeff() <= L::max_xi)) return finish(slave, f, false, iteration);
    f = patch_frame(p, x, next);
    if (converged_step(step.norm(), iteration)) return finish(slave, f, true, iteration);
  }
  return finish(slave, f, false, L::max_iterations);
}

}  // namespace stoss::contact
