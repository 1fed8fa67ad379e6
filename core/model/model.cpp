#include "core/model/model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stoss::model {

std::string to_string(Scheme s) {
  switch (s) {
    case Scheme::midpoint:
      return "midpoint";
    case Scheme::energy_momentum:
      return "energy_momentum";
    case Scheme::hht:
      return "hht";
    case Scheme::generalized_alpha:
      return "generalized_alpha";
    case Scheme::equilibrium:
      return "static";
  }
  return "unknown";
}

std::string to_string(Discretization d) {
  return d == Discretization::mortar ? "mortar" : "node_to_segment";
}

std::optional<Scheme> scheme_from_string(std::string_view name) {
  for (Scheme s : scene_schemes)
    if (to_string(s) == name) return s;
  return std::nullopt;
}

std::string to_string(LinearSolver s) {
  switch (s) {
    case LinearSolver::automatic:
      return "auto";
    case LinearSolver::direct:
      return "direct";
    case LinearSolver::iterative:
      return "iterative";
    case LinearSolver::petsc_gamg:
      return "petsc_gamg";
  }
  return "unknown";
}

std::optional<LinearSolver> linear_solver_from_string(std::string_view name) {
  for (LinearSolver s : all_linear_solvers)
    if (to_string(s) == name) return s;
  return std::nullopt;
}

namespace {

std::string impact_name(ImpactMode impact) {
  switch (impact) {
    case ImpactMode::persist:
      return "persist";
    case ImpactMode::exact:
      return "exact";
    case ImpactMode::velocity_correction:
      return "velocity_correction";
    case ImpactMode::located:
      return "located";
  }
  return "unknown";
}

}  // namespace

std::optional<SchemeConflict> contact_scheme_conflict(Scheme scheme, Enforcement enforcement,
                                                      ImpactMode impact) {
  const std::string name = "\"" + to_string(scheme) + "\"";
  if (impact == ImpactMode::velocity_correction && scheme != Scheme::energy_momentum)
    return SchemeConflict{"impact",
                          "\"velocity_correction\" needs time.scheme \"energy_momentum\", got " + name};
  if (enforcement == Enforcement::penalty && (scheme == Scheme::hht || scheme == Scheme::generalized_alpha))
    return SchemeConflict{"enforcement", "\"penalty\" is not implemented with time.scheme " + name +
                                             "; use energy_momentum or midpoint"};
  // Static steps have no impacts: a Lagrange pair closes its gap at each load level (docs/theory.md §5b.6).
  if (scheme == Scheme::equilibrium && enforcement == Enforcement::lagrange && impact != ImpactMode::exact)
    return SchemeConflict{"impact",
                          "must be \"exact\" with time.scheme \"static\" (no impacts: the gap closes at "
                          "each load level; \"exact\" is the default there), got \"" +
                              impact_name(impact) + "\""};
  return std::nullopt;
}

long long step_count(double end, double step) {
  if (!(step > 0) || !(end > 0) || !std::isfinite(end) || !std::isfinite(step)) return 0;
  const double quotient = end / step;
  if (!(quotient < static_cast<double>(max_step_count))) return max_step_count;
  // Within round-off of an integer, that integer (end = 1, step = 0.01 → 100, not 101).
  const double tolerance = std::max(1e-9, 1e-15 * quotient);
  return std::max(1LL, static_cast<long long>(std::ceil(quotient - tolerance)));
}

long long step_bound(double end, double step, std::optional<double> min_step,
                     std::optional<double> interval) {
  const long long steps = min_step && *min_step > 0 ? step_count(end, *min_step) : step_count(end, step);
  if (!interval || !(*interval > 0)) return steps;
  return std::min(max_step_count, steps + step_count(end, *interval));  // a clipped step per frame at most
}

long long OutputSpec::frame_count(long long steps, double end) const {
  if (interval) return step_count(end, *interval) + 1;
  const long long e = std::max(every, 1);
  return steps / e + 1 + (steps % e != 0 ? 1 : 0);
}

int TimeSpec::steps() const {
  return static_cast<int>(std::min<long long>(step_count(end, step), std::numeric_limits<int>::max()));
}

bool Model::has_effect(const std::string& e) const {
  return std::find(effects.begin(), effects.end(), e) != effects.end();
}

std::vector<std::string> resolve_effects(const Model& m) {
  const bool statics = m.time.scheme == Scheme::equilibrium;
  std::vector<std::string> out{statics ? effect::static_steps : effect::inertia, effect::elasticity};
  if (m.gravity && m.gravity->norm() > 0) out.push_back(effect::gravity);
  if (!m.boundary.empty()) out.push_back(effect::dirichlet);
  if (std::any_of(m.boundary.begin(), m.boundary.end(), [](const Boundary& b) { return b.moves(); }))
    out.push_back(effect::prescribed_motion);
  for (const auto kind : {Load::Kind::pressure, Load::Kind::traction})
    if (std::any_of(m.loads.begin(), m.loads.end(), [kind](const Load& l) { return l.kind == kind; }))
      out.push_back(kind == Load::Kind::pressure ? effect::pressure : effect::traction);
  const bool frictionless =
      std::any_of(m.contact.begin(), m.contact.end(), [](const ContactPair& c) { return c.friction == 0; });
  const bool frictional =
      std::any_of(m.contact.begin(), m.contact.end(), [](const ContactPair& c) { return c.friction > 0; });
  if (frictionless) out.push_back(effect::contact_frictionless);
  if (frictional) out.push_back(effect::contact_frictional);
  for (const ContactPair& c : m.contact)  // which pairs: "contact_frictional:<slave>,<master>"
    if (c.friction > 0)
      out.push_back(std::string(effect::contact_frictional) + ":" + c.slave + "," + c.master);
  return out;
}

}  // namespace stoss::model
