#pragma once
/// @file The contact module's entry point: the contact term of a pair for a time scheme.

#include <memory>

#include "core/contact/contact_mass.hpp"
#include "core/contact/lagrange/lagrange_term.hpp"
#include "core/mesh/mesh.hpp"
#include "core/model/model.hpp"

namespace stoss::contact {

/// The frictionless Lagrange term of `pair` for `scheme` (docs/theory.md §4): the mixed
/// energy–momentum form (§4.3) for energy_momentum, the midpoint NTS form (§4.2) for midpoint, the
/// HHT-α form of (2.11) for hht (hht_term.hpp).
/// @throws std::invalid_argument, naming the pair, for what is not implemented: penalty enforcement or
///         friction (those go through make_pair_term), and impact velocity_correction with midpoint or hht (the correction (4.12)
///         restores the energy identity (4.11) of the mixed form only).
std::unique_ptr<LagrangeContactTerm> make_contact_term(const mesh::Mesh& mesh, const model::ContactPair& pair,
                                                       model::Scheme scheme);

/// The contact term of `pair` in the run of model `m`: PenaltyContactTerm (penalty_term.hpp, §5) for
/// enforcement penalty, with the default stiffnesses 10 E ℓ from the master body's Young's modulus E;
/// make_contact_term for lagrange.
/// @throws std::invalid_argument, naming the pair, for penalty contact with the hht scheme (not
///         implemented), and whatever make_contact_term throws.
std::unique_ptr<ContactTerm> make_pair_term(const model::Model& m, const model::ContactPair& pair);

}  // namespace stoss::contact
