#pragma once
/// @file The contact module's entry point: the contact term of a pair for a time scheme.

#include <memory>

#include "core/contact/lagrange_term.hpp"
#include "core/mesh/mesh.hpp"
#include "core/model/model.hpp"

namespace stoss::contact {

/// The frictionless Lagrange term of `pair` for `scheme` (formulation.md §4): the mixed
/// energy–momentum form (§4.3) for energy_momentum, the midpoint NTS form (§4.2) for midpoint.
/// @throws std::invalid_argument, naming the pair, for what is not implemented: penalty enforcement or
///         friction (§5), contact with the hht scheme, and impact velocity_correction with midpoint
///         (the correction (4.12) restores the energy identity (4.11) of the mixed form only).
std::unique_ptr<LagrangeContactTerm> make_contact_term(const mesh::Mesh& mesh, const model::ContactPair& pair,
                                                       model::Scheme scheme);

}  // namespace stoss::contact
