#include "core/run/checks.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>

namespace stoss::run {
namespace {

/// Shortest element edge of the reference mesh: the scale a penetration is measured against.
double shortest_edge(const mesh::Mesh& mesh) {
  // The 12 edges of a hex8 in the node order of mesh.hpp.
  static constexpr int edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                       {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  double shortest = std::numeric_limits<double>::infinity();
  for (const mesh::Hex& hex : mesh.hex8)
    for (const auto& e : edges)
      shortest = std::min(shortest, (mesh.nodes[hex[e[0]]] - mesh.nodes[hex[e[1]]]).norm());
  return shortest;
}

bool has_friction(const model::Model& m) {
  return std::any_of(m.contact.begin(), m.contact.end(),
                     [](const model::ContactPair& p) { return p.friction > 0; });
}

/// Slave nodes over every contact pair (a node in two pairs counts twice); a pair naming a surface the
/// mesh does not hold counts none.
double contact_nodes(const model::Model& m) {
  double nodes = 0;
  for (const model::ContactPair& p : m.contact) {
    const int b = m.mesh.find_body(p.slave.substr(0, p.slave.find('/')));
    if (b >= 0 && m.mesh.bodies[b].surfaces.count(p.slave.substr(p.slave.find('/') + 1)))
      nodes += static_cast<double>(m.mesh.surface_nodes(p.slave).size());
  }
  return nodes;
}

model::Check bounded(const char* name, double value, double bound) {
  return {name, value, bound, value <= bound};
}

/// The energy check of the scheme (docs/results.md, "Verdict", (V1)–(V3)).
model::Check energy_check(const model::Model& m, const model::Summary& s) {
  const double scale = std::max(s.max_abs_energy, std::numeric_limits<double>::min());
  if (m.time.scheme == model::Scheme::energy_momentum) {
    // (V1): each Newton solve leaves up to 1e-10 of max|H|; over N steps they add like a random walk
    const double bound = 1e-10 * scale * std::sqrt(std::max(1.0, double(s.steps)));
    if (has_friction(m))  // (V2): H + D − ΣJ never rises
      return bounded("energy_plus_dissipated_rise", s.energy_balance_rise, bound);
    return bounded("energy_balance", s.energy_balance_error, bound);
  }
  if (m.time.scheme == model::Scheme::midpoint)  // (V3): not conserving, but within 1 %
    return bounded("energy_balance", s.energy_balance_error, 1e-2 * scale);
  // (V3): HHT-α and generalized-α dissipate; a gain of more than 1 % is not theirs
  return bounded("energy_gain", s.energy_balance_rise, 1e-2 * scale);
}

/// ξ_a of the hex8's corners in VTK order (docs/theory.md §1.1).
constexpr int corner_sign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                   {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

using Corners = std::array<Eigen::Vector3d, 8>;

Corners corners_of(const mesh::Hex& h, const Eigen::VectorXd& x) {
  Corners c;
  for (int a = 0; a < 8; ++a) c[a] = x.segment<3>(3 * h[a]);
  return c;
}

/// How far each side of an element may be approached: |ξ| ≤ 1 − inside_margin at a side on the body's
/// boundary, |ξ| ≤ 1 + 1e-9 at a side shared with a neighbour (a node on an interior face is inside the
/// body).
using SideLimits = std::array<double, 6>;  // in mesh::hex_faces order: ζ−, ζ+, η−, η+, ξ−, ξ+

/// Side limits of every element: a side is on the boundary when no other element has its four nodes.
std::vector<SideLimits> side_limits(const std::vector<mesh::Hex>& hex8) {
  std::map<std::array<int, 4>, int> count;
  const auto key = [](mesh::Quad q) { return std::sort(q.begin(), q.end()), q; };
  for (const mesh::Hex& h : hex8)
    for (const mesh::Quad& q : mesh::hex_faces(h)) ++count[key(q)];
  std::vector<SideLimits> limits(hex8.size());
  for (size_t e = 0; e < hex8.size(); ++e) {
    const auto faces = mesh::hex_faces(hex8[e]);
    for (int f = 0; f < 6; ++f) limits[e][f] = count[key(faces[f])] == 1 ? 1 - inside_margin : 1 + 1e-9;
  }
  return limits;
}

/// Whether p lies inside the trilinear hex within its side limits: Newton on x(ξ) = Σ N_a(ξ) x_a = p from
/// the centre (docs/results.md, "Verdict", (V9)). No convergence (p far outside, or a degenerate element)
/// counts as outside.
bool inside_hex(const Corners& c, const SideLimits& limits, const Eigen::Vector3d& p) {
  Eigen::Vector3d xi = Eigen::Vector3d::Zero();
  for (int iteration = 0;; ++iteration) {
    Eigen::Vector3d r = -p;
    Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero();
    for (int a = 0; a < 8; ++a) {
      Eigen::Vector3d f, df;  // factors (1 + ξ_k ξ_ak) / 2 and their derivatives
      for (int k = 0; k < 3; ++k) f[k] = (1 + xi[k] * corner_sign[a][k]) / 2, df[k] = corner_sign[a][k] / 2.0;
      r += f.prod() * c[a];
      jacobian.col(0) += df[0] * f[1] * f[2] * c[a];
      jacobian.col(1) += f[0] * df[1] * f[2] * c[a];
      jacobian.col(2) += f[0] * f[1] * df[2] * c[a];
    }
    Eigen::FullPivLU<Eigen::Matrix3d> lu(jacobian);
    if (!lu.isInvertible() || iteration == 30) return false;
    const Eigen::Vector3d step = lu.solve(r);
    xi -= step;
    if (xi.cwiseAbs().maxCoeff() > 3) return false;  // far outside: the map is not followed there
    if (step.cwiseAbs().maxCoeff() < 1e-12) break;
  }
  for (int k = 0; k < 3; ++k) {  // axis k is bounded by sides 4 − 2k (−) and 5 − 2k (+)
    if (-xi[k] > limits[4 - 2 * k] || xi[k] > limits[5 - 2 * k]) return false;
  }
  return true;
}

/// Elements by the cells of a uniform grid their bounding boxes overlap (cell size: the mean largest
/// box extent), so a node is tested against the few elements around it only.
class ElementGrid {
 public:
  ElementGrid(const mesh::Mesh& mesh, const Eigen::VectorXd& x) {
    low_ = Eigen::Vector3d::Constant(INFINITY);
    Eigen::Vector3d high = -low_;
    double extent_sum = 0;
    for (const mesh::Hex& h : mesh.hex8) {
      Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
      for (int n : h) lo = lo.cwiseMin(x.segment<3>(3 * n)), hi = hi.cwiseMax(x.segment<3>(3 * n));
      boxes_.push_back({lo, hi});
      low_ = low_.cwiseMin(lo), high = high.cwiseMax(hi);
      extent_sum += (hi - lo).maxCoeff();
    }
    cell_ = std::max(extent_sum / std::max<size_t>(1, boxes_.size()), std::numeric_limits<double>::min());
    for (int k = 0; k < 3; ++k) cells_[k] = 1 + static_cast<long long>((high[k] - low_[k]) / cell_);
    for (size_t e = 0; e < boxes_.size(); ++e) insert(static_cast<int>(e));
  }

  /// Elements whose bounding box holds p.
  std::vector<int> around(const Eigen::Vector3d& p) const {
    std::vector<int> out;
    const auto it = elements_.find(key(cell_of(p)));
    if (it == elements_.end()) return out;
    for (int e : it->second)
      if ((p.array() >= boxes_[e].first.array()).all() && (p.array() <= boxes_[e].second.array()).all())
        out.push_back(e);
    return out;
  }

 private:
  std::array<long long, 3> cell_of(const Eigen::Vector3d& p) const {
    std::array<long long, 3> c;
    for (int k = 0; k < 3; ++k)
      c[k] = std::clamp(static_cast<long long>((p[k] - low_[k]) / cell_), 0LL, cells_[k] - 1);
    return c;
  }
  long long key(const std::array<long long, 3>& c) const {
    return c[0] + cells_[0] * (c[1] + cells_[1] * c[2]);
  }
  void insert(int e) {
    const auto lo = cell_of(boxes_[e].first), hi = cell_of(boxes_[e].second);
    for (long long k = lo[2]; k <= hi[2]; ++k)
      for (long long j = lo[1]; j <= hi[1]; ++j)
        for (long long i = lo[0]; i <= hi[0]; ++i) elements_[key({i, j, k})].push_back(e);
  }

  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> boxes_;
  Eigen::Vector3d low_;
  double cell_ = 1;
  std::array<long long, 3> cells_{1, 1, 1};
  std::unordered_map<long long, std::vector<int>> elements_;
};

/// Body index of each node.
std::vector<int> node_bodies(const mesh::Mesh& mesh) {
  std::vector<int> body(mesh.node_count(), -1);
  for (size_t b = 0; b < mesh.bodies.size(); ++b)
    for (int n = mesh.bodies[b].node_begin; n < mesh.bodies[b].node_end; ++n) body[n] = static_cast<int>(b);
  return body;
}

}  // namespace

int nodes_inside_other_body(const mesh::Mesh& mesh, const Eigen::VectorXd& x) {
  if (mesh.bodies.size() < 2) return 0;
  const ElementGrid grid(mesh, x);
  const std::vector<int> body = node_bodies(mesh);
  const std::vector<SideLimits> limits = side_limits(mesh.hex8);
  int inside = 0;
  for (int n = 0; n < mesh.node_count(); ++n) {
    const Eigen::Vector3d p = x.segment<3>(3 * n);
    for (int e : grid.around(p))
      if (mesh.element_body[e] != body[n] && inside_hex(corners_of(mesh.hex8[e], x), limits[e], p)) {
        ++inside;
        break;
      }
  }
  return inside;
}

double newton_bound(const model::Model& m) {
  const double dofs = 3.0 * m.mesh.node_count();  // (V6)
  return 0.6 * m.solver.max_iterations + 2 * std::log10(std::max(1.0, dofs / 1000)) +
         2 * std::log2(1 + contact_nodes(m) / 100);
}

bool is_free(const model::Model& m) {
  return m.boundary.empty() && m.loads.empty() && !(m.gravity && m.gravity->norm() > 0);
}

/// HHT-α and generalized-α balance no work (docs/theory.md §5b.5): with loads or moving supports their
/// H − W drifts by what their weighted forces do, which is reported, not bounded.
bool balances_no_work(const model::Model& m) {
  const bool dissipative =
      m.time.scheme == model::Scheme::hht || m.time.scheme == model::Scheme::generalized_alpha;
  return dissipative && m.has_external_work();
}

std::vector<model::Check> run_checks(const model::Model& m, const model::Summary& s) {
  // Static load steps have no dynamics: no energy balance to check and no impacts to jump at.
  const bool statics = m.time.scheme == model::Scheme::equilibrium;
  std::vector<model::Check> checks;
  if (!statics && !balances_no_work(m)) checks.push_back(energy_check(m, s));
  if (!m.contact.empty() && !statics) {  // (V4): the energy reported jumps put in is small next to max |H|
    const double scale = std::max(s.max_abs_energy, std::numeric_limits<double>::min());
    checks.push_back(bounded("contact_energy_jumps", std::max(0.0, s.contact_energy_jumps), 0.05 * scale));
  }
  if (!m.contact.empty())  // (V5)
    checks.push_back(bounded("penetration", s.max_penetration, 0.5 * shortest_edge(m.mesh)));
  // (V6)–(V7)
  checks.push_back(bounded("newton_iterations_per_step", s.newton_iterations_per_step, newton_bound(m)));
  checks.push_back(bounded("reduced_steps", s.reduced_steps, 1.0 + 0.01 * s.steps));
  const bool midpoint_type =
      m.time.scheme == model::Scheme::energy_momentum || m.time.scheme == model::Scheme::midpoint;
  if (is_free(m)) {  // (V8)
    checks.push_back(bounded("linear_momentum_drift", s.linear_momentum_drift, 1e-8));
    if (midpoint_type) checks.push_back(bounded("angular_momentum_drift", s.angular_momentum_drift, 1e-8));
  } else if (midpoint_type) {  // (V10)
    checks.push_back(bounded("impulse_balance", s.impulse_balance_error, 1e-8));
  }
  return checks;
}

std::vector<model::Check> run_checks(const model::Model& m, const model::Summary& s,
                                     const Eigen::VectorXd& x) {
  std::vector<model::Check> checks = run_checks(m, s);
  if (m.mesh.bodies.size() > 1)  // (V9)
    checks.push_back(bounded("nodes_inside_other_body", nodes_inside_other_body(m.mesh, x), 0));
  return checks;
}

std::string verdict_of(const std::vector<model::Check>& checks) {
  const bool ok = std::all_of(checks.begin(), checks.end(), [](const model::Check& c) { return c.passed; });
  return ok ? "ok" : "suspect";
}

void add_verdict(const model::Model& m, model::Summary& s) {
  s.checks = run_checks(m, s);
  s.verdict = verdict_of(s.checks);
}

void add_verdict(const model::Model& m, model::Summary& s, const Eigen::VectorXd& x) {
  s.checks = run_checks(m, s, x);
  s.verdict = verdict_of(s.checks);
}

}  // namespace stoss::run
