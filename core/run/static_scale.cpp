#include "core/run/static_scale.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace stoss::run {
namespace {

/// Σ |vector area| of a surface's faces in the reference configuration; 0 for a node set (an *NSET).
double reference_area(const mesh::Mesh& mesh, const std::string& surface) {
  const std::vector<mesh::Quad>* faces = nullptr;
  try {
    faces = &mesh.surface(surface);
  } catch (const std::out_of_range&) {
    return 0;
  }
  double area = 0;
  for (const mesh::Quad& q : *faces) {
    const auto& X = mesh.nodes;
    area += 0.5 * (X[q[2]] - X[q[0]]).cross(X[q[3]] - X[q[1]]).norm();
  }
  return area;
}

/// max |a(t)| of an amplitude (5b.1), 1 without points.
double largest_factor(const std::vector<std::array<double, 2>>& amplitude) {
  if (amplitude.empty()) return 1;
  double largest = 0;
  for (const auto& point : amplitude) largest = std::max(largest, std::abs(point[1]));
  return largest;
}

double youngs_modulus_of(const model::Model& m, const std::string& surface) {
  const int body = m.mesh.find_body(surface.substr(0, surface.find('/')));
  return body >= 0 ? m.bodies[body].material.youngs_modulus : 0;
}

}  // namespace

double static_force_scale(const model::Model& m, double total_mass, double length) {
  double force = m.gravity ? m.gravity->norm() * total_mass : 0;
  for (const model::Load& l : m.loads) {
    const double size = l.kind == model::Load::Kind::pressure ? std::abs(l.pressure) : l.traction.norm();
    force += largest_factor(l.amplitude) * size * reference_area(m.mesh, l.surface);
  }
  for (const model::Boundary& b : m.boundary)
    if (b.moves())
      force += largest_factor(b.amplitude) * b.displacement.norm() * youngs_modulus_of(m, b.surface) *
               reference_area(m.mesh, b.surface) / length;
  return force;
}

double convergence_mass(const model::Model& m, const Problem& p) {
  if (m.time.scheme != model::Scheme::equilibrium) return p.total_mass;
  const double force = static_force_scale(m, p.total_mass, p.length_scale), h = m.time.step;
  if (!(force > 0)) return p.total_mass;
  return 1e4 * h * h * force / p.length_scale;  // 1e-4 m ℓ / h = h F (5b.7a)
}

}  // namespace stoss::run
