#pragma once
/// @file The rule of a static scene (docs/theory.md §5b.8): something holds every body.

#include <vector>

#include "core/model/model.hpp"
#include "core/scene/scene.hpp"

namespace stoss::scene::detail {

/// With time.scheme "static", one issue at /bodies/<i> for each body whose rigid modes the supports,
/// prescribed motions and contacts with held bodies leave free, naming the modes (loads::rigid_mode_rule);
/// none for a dynamic scheme. A contact holds only at the nodes that touch the other side at t = 0 (the
/// ones the static contact term starts active). A static step has no inertia, so such a body would be a
/// singular tangent.
std::vector<Issue> unheld_bodies(const model::Model& m);

}  // namespace stoss::scene::detail
