#pragma once
/// @file Limits: how much one request may ask of the server (flags of `stoss serve`).

#include <cstddef>
#include <optional>

#include "core/scene/scene.hpp"
#include "server/http/problem.hpp"

namespace stoss::server::http {

struct Limits {
  std::size_t max_body_bytes = 16u << 20;  ///< --max-body-bytes: request body (the scene JSON)
  int max_nodes = 200'000;                 ///< --max-nodes: mesh nodes of all bodies
  int max_steps = 100'000;                 ///< --max-steps: time steps to reach time.end
  int max_frames = 2'000;                  ///< --max-frames: output frames
  int max_queued = 1'000;                  ///< --max-queue: queued jobs before submissions get 503
  /// --max-mesh-store-bytes: bytes of all meshes stored by POST /v1/meshes; an upload beyond gets 413
  std::size_t max_mesh_store_bytes = std::size_t(1) << 30;
};

/// A 413 problem naming every limit the scene exceeds (name, limit, value), or nullopt when within all.
std::optional<Problem> check_scene_limits(const scene::Summary& scene, const Limits& limits);

/// The same check on sizes read from the scene JSON alone (generator divisions, inline node arrays,
/// time.end / time.step), before a model is built: a scene asking for 10^9 nodes is refused without
/// allocating them. Fields that are missing or of the wrong type count as 0 (validation reports them).
std::optional<Problem> check_scene_limits_early(const nlohmann::json& scene, const Limits& limits);

}  // namespace stoss::server::http
