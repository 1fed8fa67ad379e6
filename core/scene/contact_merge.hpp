#pragma once
/// @file No silent seams (docs/scene.md, "Pairs that share a slave"): contact pairs with one slave whose
/// masters belong to one body become one pair with the union master.

#include <vector>

#include "core/model/model.hpp"
#include "core/scene/checks.hpp"

namespace stoss::scene::detail {

/// Merges, in the validated scene (defaults filled in), every group of contact pairs that share a slave
/// (the same surfaces) and whose masters belong to one body into the group's first pair, its master the
/// list of all their master surfaces in order, each once. Pairs whose settings (every field but slave and
/// master) differ are an issue at the later pair naming both and the list form. Returns the merges (the
/// merged pair's index in the new list, the indices the pairs had as written).
std::vector<model::Model::MergedPairs> merge_contact_pairs(json& scene, Checker& c);

}  // namespace stoss::scene::detail
