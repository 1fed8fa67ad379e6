#include "core/contact/contact.hpp"

#include <stdexcept>

#include "core/contact/midpoint_term.hpp"
#include "core/contact/mixed_term.hpp"

namespace stoss::contact {
namespace {

void check_supported(const model::ContactPair& pair, model::Scheme scheme) {
  const std::string which = "contact pair " + pair.slave + " / " + pair.master + ": ";
  if (pair.enforcement != model::Enforcement::lagrange || pair.friction > 0)
    throw std::invalid_argument(which +
                                "penalty enforcement and friction are not implemented yet; use "
                                "enforcement \"lagrange\" with friction 0");
  if (scheme == model::Scheme::hht)
    throw std::invalid_argument(which +
                                "contact is not implemented for the hht scheme; use energy_momentum "
                                "or midpoint");
  if (scheme == model::Scheme::midpoint && pair.impact == model::ImpactMode::velocity_correction)
    throw std::invalid_argument(which +
                                "impact \"velocity_correction\" needs the energy_momentum scheme; use "
                                "\"persist\" or \"exact\" with midpoint");
}

}  // namespace

std::unique_ptr<LagrangeContactTerm> make_contact_term(const mesh::Mesh& mesh, const model::ContactPair& pair,
                                                       model::Scheme scheme) {
  check_supported(pair, scheme);
  if (scheme == model::Scheme::energy_momentum) return std::make_unique<MixedContactTerm>(mesh, pair);
  return std::make_unique<MidpointContactTerm>(mesh, pair);
}

}  // namespace stoss::contact
