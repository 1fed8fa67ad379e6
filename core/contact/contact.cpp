#include "core/contact/contact.hpp"

#include <stdexcept>

#include "core/contact/lagrange/elements/mixed_term.hpp"
#include "core/contact/lagrange/elements/nts_term.hpp"
#include "core/contact/mortar/mortar_term.hpp"
#include "core/contact/penalty/penalty_term.hpp"
#include "core/time/scheme.hpp"

namespace stoss::contact {
namespace {

std::string pair_label(const model::ContactPair& pair) {
  return "contact pair " + pair.slave + " / " + pair.master + ": ";
}

/// The scheme rules of model::contact_scheme_conflict.
void check_scheme(const model::ContactPair& pair, model::Scheme scheme) {
  if (const auto conflict = model::contact_scheme_conflict(scheme, pair.enforcement, pair.impact))
    throw std::invalid_argument(pair_label(pair) + conflict->field + " " + conflict->reason);
}

/// Young's modulus of the body that owns the master surface ("body/surface").
double master_youngs_modulus(const model::Model& m, const model::ContactPair& pair) {
  const std::string body = pair.master.substr(0, pair.master.find('/'));
  for (const model::BodySpec& b : m.bodies)
    if (b.name == body) return b.material.youngs_modulus;
  throw std::invalid_argument(pair_label(pair) + "no body named \"" + body + "\"");
}

/// The frictionless Lagrange term of the scheme's force rule (docs/theory.md §4).
std::unique_ptr<ContactTerm> make_lagrange_term(const mesh::Mesh& mesh, const model::ContactPair& pair,
                                                model::Scheme scheme) {
  if (pair.friction > 0)
    throw std::invalid_argument(
        pair_label(pair) +
        "enforcement \"lagrange\" is frictionless; friction > 0 needs enforcement \"penalty\"");
  const time::ForceRule rule = time::make_scheme(model::TimeSpec{scheme})->force_rule();
  if (pair.discretization == model::Discretization::mortar)
    return std::make_unique<MortarContactTerm>(mesh, pair, rule);  // §4.7.1, every rule
  if (rule.kind == time::ForceRule::Kind::discrete_gradient)
    return std::make_unique<MixedContactTerm>(mesh, pair);
  if (rule.is_midpoint() || rule.is_end_point())
    return std::make_unique<NtsContactTerm>(mesh, pair, rule);  // (4.2), (2.11)
  throw std::invalid_argument(
      pair_label(pair) + "no Lagrange contact element evaluates forces at θ = " + std::to_string(rule.theta) +
      " with a t_n force (time.scheme " + model::to_string(scheme) + ")");
}

}  // namespace

std::unique_ptr<ContactTerm> make_pair_term(const model::Model& m, const model::ContactPair& pair) {
  check_scheme(pair, m.time.scheme);
  if (pair.discretization == model::Discretization::mortar && pair.enforcement == model::Enforcement::penalty)
    throw std::invalid_argument(pair_label(pair) + "discretization \"mortar\" has Lagrange multipliers only");
  if (pair.enforcement != model::Enforcement::penalty) return make_lagrange_term(m.mesh, pair, m.time.scheme);
  return std::make_unique<PenaltyContactTerm>(m.mesh, pair, master_youngs_modulus(m, pair),
                                              m.time.scheme == model::Scheme::equilibrium);  // §5b.6
}

}  // namespace stoss::contact
