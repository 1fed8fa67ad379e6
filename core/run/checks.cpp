#include "core/run/checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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

}  // namespace

bool is_free(const model::Model& m) {
  return m.boundary.empty() && m.loads.empty() && !(m.gravity && m.gravity->norm() > 0);
}

std::vector<model::Check> run_checks(const model::Model& m, const model::Summary& s) {
  std::vector<model::Check> checks{energy_check(m, s)};
  if (!m.contact.empty()) {  // (V4): reported jumps are small next to H_0
    const double H0 = std::max(std::abs(s.initial_energy), std::numeric_limits<double>::min());
    checks.push_back(bounded("contact_energy_jumps", std::abs(s.contact_energy_jumps), 0.05 * H0));
  }
  if (!m.contact.empty())  // (V5)
    checks.push_back(bounded("penetration", s.max_penetration, 0.5 * shortest_edge(m.mesh)));
  // (V6)–(V7)
  checks.push_back(
      bounded("newton_iterations_per_step", s.newton_iterations_per_step, 0.6 * m.solver.max_iterations));
  checks.push_back(bounded("reduced_steps", s.reduced_steps, 1.0 + 0.01 * s.steps));
  if (is_free(m)) {  // (V8)
    checks.push_back(bounded("linear_momentum_drift", s.linear_momentum_drift, 1e-8));
    if (m.time.scheme == model::Scheme::energy_momentum || m.time.scheme == model::Scheme::midpoint)
      checks.push_back(bounded("angular_momentum_drift", s.angular_momentum_drift, 1e-8));
  }
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

}  // namespace stoss::run
