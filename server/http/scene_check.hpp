#pragma once
/// @file What POST /v1/jobs and POST /v1/validate do with a body before anything is queued.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/scene/scene.hpp"
#include "server/http/httplib.hpp"
#include "server/http/limits.hpp"

namespace stoss::server::http {

/// The header the pre-routing hook moves the client's Content-Type to (so that cpp-httplib neither
/// parses a form body nor caps it at 8 KiB: JSON is accepted whatever the declared type).
inline constexpr const char* declared_type_header = "X-Stoss-Declared-Content-Type";

/// The Content-Type the client declared, lower case, without parameters ("" when none).
std::string declared_content_type(const httplib::Request& req);

/// The 413 for a body above max_body_bytes: `limits` names max_body_bytes with its limit and the
/// body's size as `value` (when known).
Problem body_too_large(std::size_t limit, std::optional<unsigned long long> value);

/// The request body as JSON. Throws ProblemError: 413 above max_body_bytes, 400 when it is not JSON
/// (with line, column and byte offset of the first error), 400 when nested deeper than max_json_depth
/// (checked before parsing), 415 when it is neither JSON nor declared as JSON.
nlohmann::json parse_json_body(const httplib::Request& req, const Limits& limits);

/// Validates a scene and checks it against the limits; "mesh": {"id": ...} is resolved by `mesh_files`.
/// Throws ProblemError: 422 listing every scene error with its JSON pointer (also /solver/ranks above
/// max_ranks_per_job), 413 naming each exceeded limit.
/// `resolved`, when given, receives the scene with every default filled in (model::Model::scene): what a
/// job stores and its worker runs with scene::load_resolved, so that a scene is validated once per job.
scene::Summary check_scene(const nlohmann::json& scene, const Limits& limits,
                           const scene::MeshFiles& mesh_files = {}, nlohmann::json* resolved = nullptr);

}  // namespace stoss::server::http
