#pragma once
/// @file The scene validator: one check per object kind of api/scene.schema.json.

#include "core/scene/checks.hpp"

namespace stoss::scene::detail {

/// Validates `scene` in place and fills in every default; each problem found goes to `checker`.
void check_scene(json& scene, Checker& checker);

}  // namespace stoss::scene::detail
