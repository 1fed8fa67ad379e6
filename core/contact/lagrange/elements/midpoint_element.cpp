#include "core/contact/lagrange/elements/midpoint_element.hpp"

#include "core/contact/geometry/variations.hpp"

namespace stoss::contact {
namespace {
Projection project(const Vector15& x, const Eigen::Vector2d& xi_start) {
  return closest_point_projection(slave_position(x), segment_nodes(x), xi_start);
}
}  // namespace

MidpointResult midpoint_element(const Vector15& x_n, const Vector15& x_1, double lambda, double f3, double h,
                                const Eigen::Vector2d& xi_start) {
  MidpointResult out;
  out.mid = project(0.5 * (x_n + x_1), xi_start);
  out.end = project(x_1, xi_start);
  out.converged = out.mid.converged && out.end.converged;
  const GapVariations mid = gap_variations(out.mid.frame, out.mid.gap);
  out.Rx = h * lambda * mid.Ns;                       // (4.2)
  out.Rl = out.end.gap - f3;                          // (4.2)
  out.Kxx = 0.5 * h * lambda * mid.dNs;               // (4.2), (3.9)
  out.Kxl = h * mid.Ns;                               // (4.2)
  out.Klx = gap_gradient(out.end.frame).transpose();  // (4.2), (3.6)
  return out;
}

}  // namespace stoss::contact
