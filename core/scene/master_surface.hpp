#pragma once
/// @file The master surface of each contact pair, resolved once the mesh exists
/// (docs/smooth_master_surface.md §1).

#include <optional>
#include <string>
#include <vector>

#include "core/model/model.hpp"

namespace stoss::scene::detail {

/// Why pair `p` cannot use the smooth surface (naming the node or edge that breaks the rules), or nothing.
std::optional<std::string> smooth_unavailable(const model::Model& m, const model::ContactPair& p);

/// For each pair of m.contact (after the merge of pairs that share a slave, m.merged_contact), its index in
/// the scene as written: where a problem with the pair is reported.
std::vector<int> written_contact_indices(const model::Model& m);

/// Resolves every pair's `master_surface` and `switch_gap` and writes them into the model and into its
/// resolved scene: `smooth` by default wherever it is implemented (enforcement lagrange, every scheme)
/// and the master surface qualifies (contact/smooth_surface.hpp),
/// `faceted` otherwise and always for a mortar pair (it integrates on the faceted surface, theory.md §4.7);
/// `switch_gap` defaults to `keep` on a smooth surface (a switch then costs no energy and the gap it keeps is
/// tiny, §3.3) and to `clamp` on a faceted one.
/// @throws SceneError at /contact/<i>/master_surface (i the pair's index as written) where "smooth" was asked
/// for and cannot be had,
///         naming the reason (penalty enforcement, or the node or edge that breaks the
///         surface rules).
void resolve_master_surfaces(model::Model& m);

}  // namespace stoss::scene::detail
