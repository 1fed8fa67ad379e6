#pragma once
/// @file What POST /v1/studies does with a body before anything is queued: validate the study's fields and
/// its scene, and check the runs against the server limits.

#include <nlohmann/json.hpp>

#include "core/scene/scene.hpp"
#include "core/study/study.hpp"
#include "server/http/limits.hpp"

namespace stoss::server::http {

/// Most step sizes one study may sweep (a validation rule: `/steps` with more is 422).
inline constexpr std::size_t max_study_steps = 100;

/// A study request that passed every check.
struct StudyRequest {
  nlohmann::json scene;    ///< the scene as submitted, every default filled in (what the worker runs)
  study::Options options;  ///< defaults filled in: all three schemes, reference_step = min(steps) / 32
  scene::Summary summary;  ///< of the scene (effects, nodes, …)
  int runs = 0;  ///< study::run_count: the reference run plus `repeat` per scheme × (step or tolerance)
};

/// Validates `{"scene": {...}, "steps": [h...], "tolerances": [TOL...]?, "schemes": [...]?, "reference_step":
/// H?, "repeat": N?}`. Throws ProblemError: 422 (`urn:stoss:problem:invalid-study`) listing every error by
/// JSON pointer into the body (scene errors under `/scene`, `/scene/solver/ranks` above 1: a study runs on
/// one rank, `/steps/i`, `/tolerances/i`, `/schemes/i`, `/reference_step`, unknown members); 413 naming the
/// limit when the scene exceeds max_nodes or the study's finest run (the reference, a finer swept step, or
/// with tolerances end/min_step) exceeds max_steps. The scene's own time.step and output frames are not
/// checked against max_steps and max_frames: a study replaces the step and writes no frames. Mesh ids of the
/// scene are resolved by `mesh_files`.
StudyRequest check_study(const nlohmann::json& body, const Limits& limits,
                         const scene::MeshFiles& mesh_files = {});

}  // namespace stoss::server::http
