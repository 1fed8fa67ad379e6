#pragma once
/// @file Limits: how much one request may ask of the server (flags of `stoss serve`), and reading a
/// request body within them.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "core/scene/scene.hpp"
#include "server/http/httplib.hpp"
#include "server/http/problem.hpp"

namespace stoss::server::http {

struct Limits {
  std::size_t max_body_bytes = 16u << 20;  ///< --max-body-bytes: request body (the scene JSON)
  int max_nodes = 200'000;                 ///< --max-nodes: mesh nodes of all bodies
  int max_steps = 100'000;                 ///< --max-steps: time steps to reach time.end
  int max_frames = 2'000;                  ///< --max-frames: output frames
  int max_ranks_per_job = 1;               ///< --max-ranks-per-job: MPI ranks a scene may ask for (422 above)
  int max_queued = 1'000;                  ///< --max-queue: queued jobs before submissions get 503
  /// --request-timeout: longest time from a request's head to the last byte of its body.
  std::chrono::milliseconds request_timeout{60'000};
  /// --max-mesh-store-bytes: bytes of all meshes stored by POST /v1/meshes; an upload beyond gets 413
  std::size_t max_mesh_store_bytes = std::size_t(1) << 30;
};

/// Counts a scene asks for, 64-bit: what a 413 reports is the count itself, never a saturated int.
struct SceneCounts {
  long long nodes = 0;
  long long steps = 0;
  long long frames = 0;
};

/// A 413 problem naming every limit the scene exceeds (name, limit, value), or nullopt when within all.
std::optional<Problem> check_scene_limits(const SceneCounts& scene, const Limits& limits);
std::optional<Problem> check_scene_limits(const scene::Summary& scene, const Limits& limits);

/// The counts read from the scene JSON alone (generator divisions, inline node arrays, time.end /
/// time.step with model::step_count, output.every), before a model is built. Fields that are missing or
/// of the wrong type count as 0 (validation reports them); a count beyond 64 bits saturates.
SceneCounts estimate_scene_counts(const nlohmann::json& scene);

/// The same check on estimate_scene_counts: a scene asking for 10^9 nodes is refused without allocating
/// them.
std::optional<Problem> check_scene_limits_early(const nlohmann::json& scene, const Limits& limits);

/// The 408 for a request whose body was still arriving `request_timeout` after its head.
Problem request_too_slow(std::chrono::milliseconds request_timeout, std::uint64_t received);

/// Reads a request body through cpp-httplib's content reader, counting the bytes as they arrive (after
/// any Content-Encoding is undone): reading stops at the first byte beyond max_body_bytes (413) or at the
/// first bytes that arrive after `deadline` (408), so no more than max_body_bytes are ever held.
/// Throws ProblemError: 413, 408, 415 for a
/// Content-Encoding cpp-httplib cannot undo, 400 for a body cut off or with broken chunked framing
/// (`res` holds cpp-httplib's status after a failed read).
std::string read_body_within_limits(const httplib::ContentReader& reader, const Limits& limits,
                                    std::chrono::steady_clock::time_point deadline,
                                    const httplib::Response& res);

}  // namespace stoss::server::http
