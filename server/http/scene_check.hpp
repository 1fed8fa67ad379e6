#pragma once
/// @file What POST /v1/jobs and POST /v1/validate do with a body before anything is queued.

#include <nlohmann/json.hpp>

#include "core/scene/scene.hpp"
#include "server/http/httplib.hpp"
#include "server/http/limits.hpp"

namespace stoss::server::http {

/// The request body as JSON. Throws ProblemError: 413 above max_body_bytes, 400 when it is not JSON
/// (with line, column and byte offset of the first error).
nlohmann::json parse_json_body(const httplib::Request& req, const Limits& limits);

/// Validates a scene and checks it against the limits. Throws ProblemError: 422 listing every scene
/// error with its JSON pointer, 413 naming each exceeded limit.
scene::Summary check_scene(const nlohmann::json& scene, const Limits& limits);

}  // namespace stoss::server::http
