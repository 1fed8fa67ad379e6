#pragma once
/// @file Checks before the run (docs/scene.md, "Checks before the run"): what in a valid scene looks
/// like a mistake, as warnings with a JSON pointer and a suggested fix, and the choices loading made.

#include <vector>

#include "core/model/model.hpp"
#include "core/scene/estimates.hpp"
#include "core/scene/scene.hpp"

namespace stoss::scene {

/// Warning codes (a contract: clients match on them).
namespace warning {
inline constexpr const char* contact_behind_master = "contact_behind_master";
inline constexpr const char* unit_scale = "unit_scale";
inline constexpr const char* step_longer_than_contact = "step_longer_than_contact";
inline constexpr const char* step_longer_than_modes = "step_longer_than_modes";
inline constexpr const char* step_far_below_waves = "step_far_below_waves";
inline constexpr const char* mesh_elements_skipped = "mesh_elements_skipped";
}  // namespace warning

/// Every warning of a loaded model: elements a body's mesh file left out, orientation of each contact
/// pair, then the scales of `estimates`.
std::vector<Warning> warnings(const model::Model& model, const Estimates& estimates);

/// Each contact pair's master_surface and switch_gap, and why it got them.
std::vector<ResolvedChoice> resolved_choices(const model::Model& model);

/// What a dry run tells before the run, as the API and `stoss validate --json` show it (docs/api.md):
/// {"warnings": [{code, pointer, message}], "choices": [{pointer, value, reason}], "estimates": {...}}.
nlohmann::json before_run_json(const Summary& summary);

}  // namespace stoss::scene
