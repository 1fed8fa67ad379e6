#pragma once
/// @file The contact module's entry point: the contact term of a pair for a time scheme.

#include <memory>

#include "core/contact/contact_mass.hpp"
#include "core/contact/contact_term.hpp"
#include "core/mesh/mesh.hpp"
#include "core/model/model.hpp"

namespace stoss::contact {

/// The module's one factory: the contact term of `pair` in the run of model `m`.
/// - enforcement penalty: PenaltyContactTerm (penalty_term.hpp, §5), with the default stiffnesses
///   10 E ℓ from the master body's Young's modulus E;
/// - enforcement lagrange: the frictionless Lagrange term (docs/theory.md §4) of the scheme's force
///   rule: the mixed energy–momentum form (§4.3) for the discrete gradient, the midpoint NTS form
///   (§4.2) for midpoint forces, the end-point form of (2.11), (2.12) for hht and generalized_alpha;
/// - discretization mortar: MortarContactTerm (mortar_term.hpp, §4.7.1), Lagrange and frictionless, for
///   every scheme (penalty enforcement or friction > 0 with it throw, as validation refuses them).
/// @throws std::invalid_argument, naming the pair, for what is not implemented: penalty contact with
///         hht, lagrange with friction > 0, and impact velocity_correction with midpoint or hht (the
///         correction (4.12) restores the energy identity (4.11) of the mixed form only).
std::unique_ptr<ContactTerm> make_pair_term(const model::Model& m, const model::ContactPair& pair);

}  // namespace stoss::contact
