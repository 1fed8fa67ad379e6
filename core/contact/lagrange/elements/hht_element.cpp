#include "core/contact/lagrange/elements/hht_element.hpp"

#include "core/contact/geometry/variations.hpp"

namespace stoss::contact {
namespace {
Projection project(const Vector15& x, const Eigen::Vector2d& xi_start) {
  return closest_point_projection(slave_position(x), segment_nodes(x), xi_start);
}
}  // namespace

HhtElementResult hht_element(const Vector15& x_1, double lambda, double f3, double h, double weight,
                             const Eigen::Vector2d& xi_start) {
  HhtElementResult out;
  out.end = project(x_1, xi_start);
  out.converged = out.end.converged;
  const GapVariations end = gap_variations(out.end.frame, out.end.gap);
  const double step_weight = h * weight;     // (2.11), (2.12): w on the t_{n+1} forces
  out.Rx = step_weight * lambda * end.Ns;    // (2.11), (3.6)
  out.Rl = out.end.gap - f3;                 // (2.11): g(x_{n+1}) = 0 for active constraints
  out.Kxx = step_weight * lambda * end.dNs;  // (3.9)
  out.Kxl = step_weight * end.Ns;            // (3.6)
  out.Klx = end.Ns.transpose();              // (3.6)
  return out;
}

Vector15 hht_element_force(const Vector15& x, double lambda, const Eigen::Vector2d& xi_start) {
  const Projection p = project(x, xi_start);
  if (!p.converged) return Vector15::Zero();
  return lambda * gap_gradient(p.frame);  // λ N_s (3.6)
}

}  // namespace stoss::contact
