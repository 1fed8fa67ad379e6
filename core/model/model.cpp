#include "core/model/model.hpp"

#include <algorithm>
#include <cmath>

namespace stoss::model {

std::string to_string(Scheme s) {
  switch (s) {
    case Scheme::midpoint: return "midpoint";
    case Scheme::energy_momentum: return "energy_momentum";
    case Scheme::hht: return "hht";
    case Scheme::generalized_alpha: return "generalized_alpha";
  }
  return "unknown";
}

std::optional<Scheme> scheme_from_string(std::string_view name) {
  for (Scheme s : all_schemes)
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

std::optional<SchemeConflict> contact_scheme_conflict(Scheme scheme, Enforcement enforcement, ImpactMode impact) {
  const std::string name = "\"" + to_string(scheme) + "\"";
  if (impact == ImpactMode::velocity_correction && scheme != Scheme::energy_momentum)
    return SchemeConflict{"impact", "\"velocity_correction\" needs time.scheme \"energy_momentum\", got " + name};
  if (enforcement == Enforcement::penalty && (scheme == Scheme::hht || scheme == Scheme::generalized_alpha))
    return SchemeConflict{"enforcement", "\"penalty\" is not implemented with time.scheme " + name +
                                             "; use energy_momentum or midpoint"};
  return std::nullopt;
}

int TimeSpec::steps() const {
  if (step <= 0 || end <= 0) return 0;
  // A step count within round-off of an integer is that integer (end = 1, step = 0.01 → 100).
  return static_cast<int>(std::ceil(end / step - 1e-9));
}

bool Model::has_effect(const std::string& e) const {
  return std::find(effects.begin(), effects.end(), e) != effects.end();
}

std::vector<std::string> resolve_effects(const Model& m) {
  std::vector<std::string> out{effect::inertia, effect::elasticity};
  if (m.gravity && m.gravity->norm() > 0) out.push_back(effect::gravity);
  if (!m.boundary.empty()) out.push_back(effect::dirichlet);
  const bool frictionless = std::any_of(m.contact.begin(), m.contact.end(),
                                        [](const ContactPair& c) { return c.friction == 0; });
  const bool frictional = std::any_of(m.contact.begin(), m.contact.end(),
                                      [](const ContactPair& c) { return c.friction > 0; });
  if (frictionless) out.push_back(effect::contact_frictionless);
  if (frictional) out.push_back(effect::contact_frictional);
  for (const ContactPair& c : m.contact)  // which pairs: "contact_frictional:<slave>,<master>"
    if (c.friction > 0)
      out.push_back(std::string(effect::contact_frictional) + ":" + c.slave + "," + c.master);
  return out;
}

}  // namespace stoss::model
