#pragma once
/// @file The mass a run integrates with when Lagrange pairs use impact "located" under a midpoint-type
/// scheme: the nodes of both their surfaces carry no inertia (docs/theory.md §4.6.1).

#include <vector>

#include "core/model/model.hpp"
#include "core/solve/block_pattern.hpp"

namespace stoss::contact {

/// Nodes made massless by the model's pairs: the slave and master nodes of every Lagrange pair with impact
/// located, when the scheme is energy_momentum or midpoint (the end-point schemes need M regular for a_0).
/// Sorted.
std::vector<int> massless_nodes(const model::Model& m);

/// M' = Pᵀ M P (§4.6.1): P copies to each massless node the mean velocity of its nearest (reference
/// distance) nodes off the massless set that share an element with it, and is the identity elsewhere.
/// M' is symmetric, has zero rows and columns at massless nodes and keeps the total mass; M ⊗ 1₃ stays
/// M' ⊗ 1₃, so both momenta stay conserved. Returns M when no node is massless.
/// @throws std::invalid_argument naming the node when a massless node shares no element with a node that is
/// not.
solve::SparseMatrix contact_mass(const model::Model& m, const solve::SparseMatrix& M);

/// P of (4.13) on the dofs (3 per node), or an empty matrix when no node is massless. The run sets
/// v ← P v after each step: a massless node's velocity is then its donors' mean (M'v does not see it, so
/// energy and momenta are untouched), and the predictor moves it with them (§4.6.1).
/// @throws std::invalid_argument as contact_mass.
solve::SparseMatrix massless_velocity_map(const model::Model& m);

}  // namespace stoss::contact
