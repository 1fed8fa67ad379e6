#include "core/scene/estimates.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

namespace stoss::scene {
namespace {

/// The 12 edges of a hex8 in VTK order (docs/theory.md §1.1).
constexpr int hex_edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                  {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

/// Volume of a hex8 from its Jacobian at the centre, 8 det J(0) (exact for parallelepipeds).
double hex_volume(const mesh::Mesh& mesh, const mesh::Hex& h) {
  constexpr int sign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                              {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
  for (int a = 0; a < 8; ++a)
    for (int k = 0; k < 3; ++k) j.col(k) += sign[a][k] / 8.0 * mesh.nodes[h[a]];
  return 8 * std::abs(j.determinant());
}

bool has_support(const model::Model& m, const std::string& body) {
  return std::any_of(m.boundary.begin(), m.boundary.end(), [&](const model::Boundary& b) {
    return b.surface.substr(0, b.surface.find('/')) == body;
  });
}

BodyScale body_scale(const model::Model& m, size_t b) {
  const mesh::Body& body = m.mesh.bodies[b];
  const model::Material& mat = m.bodies[b].material;
  BodyScale s;
  s.name = body.name;
  const double e = mat.youngs_modulus, nu = mat.poisson_ratio, rho = mat.density;
  s.bar_speed = std::sqrt(e / rho);                                                  // (W1)
  s.dilatational_speed = std::sqrt(e * (1 - nu) / (rho * (1 + nu) * (1 - 2 * nu)));  // (W1)
  s.smallest_element = std::numeric_limits<double>::infinity();
  double volume = 0;
  for (int el = body.element_begin; el < body.element_end; ++el) {
    const mesh::Hex& h = m.mesh.hex8[el];
    for (const auto& edge : hex_edges)
      s.smallest_element =
          std::min(s.smallest_element, (m.mesh.nodes[h[edge[0]]] - m.mesh.nodes[h[edge[1]]]).norm());
    volume += hex_volume(m.mesh, h);
  }
  s.mass = rho * volume;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(INFINITY), high = -low, sum = Eigen::Vector3d::Zero();
  for (int n = body.node_begin; n < body.node_end; ++n) {
    low = low.cwiseMin(m.mesh.nodes[n]);
    high = high.cwiseMax(m.mesh.nodes[n]);
    sum += m.mesh.nodes[n];
  }
  s.extent = high - low;
  s.centroid = sum / std::max(1, body.node_end - body.node_begin);
  s.courant = s.dilatational_speed * m.time.step / s.smallest_element;  // (W2)
  s.lowest_period = 2 * s.extent.maxCoeff() / s.bar_speed;              // (W3)
  s.supported = has_support(m, body.name);
  return s;
}

/// Smallest distance between a node of surface `a` and one of surface `b` (at most ~400 nodes of `a`).
double surface_gap(const mesh::Mesh& mesh, const std::string& a, const std::string& b) {
  const std::vector<int> from = mesh.surface_nodes(a), to = mesh.surface_nodes(b);
  const size_t stride = std::max<size_t>(1, from.size() / 400);
  double gap = INFINITY;
  for (size_t i = 0; i < from.size(); i += stride)
    for (int j : to) gap = std::min(gap, (mesh.nodes[from[i]] - mesh.nodes[j]).norm());
  return gap;
}

const BodyScale& scale_of(const std::vector<BodyScale>& bodies, const std::string& surface) {
  const std::string body = surface.substr(0, surface.find('/'));
  return *std::find_if(bodies.begin(), bodies.end(), [&](const BodyScale& s) { return s.name == body; });
}

/// Speed at which the slave closes on the master along the line between their centroids; a fall under
/// gravity across the gap adds √(2 g·d gap).
double approach_speed(const model::Model& m, const model::ContactPair& p, const BodyScale& slave,
                      const BodyScale& master) {
  const Eigen::Vector3d d = (master.centroid - slave.centroid).normalized();
  const auto velocity = [&](const BodyScale& s) {
    return m.bodies[m.mesh.find_body(s.name)].initial_velocity;
  };
  const double v = (velocity(slave) - velocity(master)).dot(d);
  const double g = m.gravity && !slave.supported ? m.gravity->dot(d) : 0;
  if (g <= 0) return std::max(0.0, v);
  return std::sqrt(std::max(0.0, v) * std::max(0.0, v) + 2 * g * surface_gap(m.mesh, p.slave, p.master));
}

PairScale pair_scale(const model::Model& m, size_t i, const std::vector<BodyScale>& bodies) {
  const model::ContactPair& p = m.contact[i];
  const BodyScale& slave = scale_of(bodies, p.slave);
  const BodyScale& master = scale_of(bodies, p.master);
  const model::Material& ms = m.bodies[m.mesh.find_body(slave.name)].material;
  const model::Material& mm = m.bodies[m.mesh.find_body(master.name)].material;
  PairScale s;
  s.pair = i;
  s.slave = p.slave;
  s.master = p.master;
  s.approach_speed = approach_speed(m, p, slave, master);
  if (!(s.approach_speed > 0)) return s;
  const double contact_modulus = 1 / ((1 - ms.poisson_ratio * ms.poisson_ratio) / ms.youngs_modulus +
                                      (1 - mm.poisson_ratio * mm.poisson_ratio) / mm.youngs_modulus);
  const double master_inverse_mass = master.supported ? 0 : 1 / master.mass;
  const double reduced_mass = 1 / (1 / slave.mass + master_inverse_mass);
  const double radius = slave.extent.minCoeff() / 2;
  const double v0 = s.approach_speed;
  const double indentation =
      std::pow(15 * reduced_mass * v0 * v0 / (16 * contact_modulus * std::sqrt(radius)), 0.4);
  s.hertz_duration = 2.94 * indentation / v0;  // (W4)
  const Eigen::Vector3d d = (master.centroid - slave.centroid).normalized();
  s.wave_duration = 2 * slave.extent.cwiseProduct(d.cwiseAbs()).sum() / slave.bar_speed;  // (W5)
  s.duration = std::max(s.hertz_duration, s.wave_duration);                               // (W6)
  return s;
}

/// S_f of (W7): slave nodes of every pair, a frictional pair's counted twice, a mortar pair's 1.9 times.
double weighted_slave_nodes(const model::Model& m) {
  double nodes = 0;
  for (const model::ContactPair& p : m.contact) {
    const double weight = p.discretization == model::Discretization::mortar ? estimate_mortar_weight
                          : p.friction > 0                                  ? 2.0
                                                                            : 1.0;
    nodes += weight * static_cast<double>(m.mesh.surface_nodes(p.slave).size());
  }
  return nodes;
}

}  // namespace

double run_seconds(double steps, double elements, double courant, double weighted_slave_nodes) {
  const double element_seconds = estimate_element_seconds * std::pow(elements, estimate_element_exponent) *
                                 (1 + estimate_courant_factor * std::log10(1 + courant));
  return estimate_setup_seconds +
         steps * (element_seconds + estimate_slave_node_seconds * weighted_slave_nodes);  // (W7)
}

Estimates estimate(const model::Model& m) {
  Estimates e;
  for (size_t b = 0; b < m.mesh.bodies.size(); ++b) e.bodies.push_back(body_scale(m, b));
  for (size_t i = 0; i < m.contact.size(); ++i) {
    e.slave_nodes += m.mesh.surface_nodes(m.contact[i].slave).size();
    if (PairScale p = pair_scale(m, i, e.bodies); p.approach_speed > 0) e.pairs.push_back(p);
  }
  double courant = 0;
  for (const BodyScale& b : e.bodies) courant = std::max(courant, b.courant);
  e.wall_seconds = run_seconds(m.time.steps(), m.mesh.element_count(), courant, weighted_slave_nodes(m));
  return e;
}

nlohmann::json to_json(const Estimates& e) {
  nlohmann::json bodies = nlohmann::json::array(), pairs = nlohmann::json::array();
  for (const BodyScale& b : e.bodies)
    bodies.push_back({{"name", b.name},
                      {"wave_speed", b.dilatational_speed},
                      {"bar_wave_speed", b.bar_speed},
                      {"smallest_element", b.smallest_element},
                      {"courant_number", b.courant},
                      {"lowest_period", b.lowest_period}});
  for (const PairScale& p : e.pairs)
    pairs.push_back({{"pointer", "/contact/" + std::to_string(p.pair)},
                     {"slave", p.slave},
                     {"master", p.master},
                     {"approach_speed", p.approach_speed},
                     {"hertz_duration", p.hertz_duration},
                     {"wave_duration", p.wave_duration},
                     {"contact_duration", p.duration}});
  return {{"bodies", bodies},
          {"contact", pairs},
          {"slave_nodes", e.slave_nodes},
          {"wall_seconds", e.wall_seconds}};
}

}  // namespace stoss::scene
