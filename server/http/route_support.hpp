#pragma once
/// @file What several route files share: problem replies, JSON answers, the job a path names, mesh files for
/// the scene checks, query parameters, files read whole or streamed with byte ranges.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/scene.hpp"
#include "server/http/httplib.hpp"
#include "server/http/routes.hpp"

namespace stoss::server::http {

inline constexpr const char* json_type = "application/json";

/// Throws the problem+json answer `status` of kind urn:stoss:problem:<kind>.
[[noreturn]] void fail(int status, const std::string& kind, const std::string& title,
                       const std::string& detail);

/// Answers `body` as application/json with `status`.
void send_json(httplib::Response& res, int status, const nlohmann::json& body);

/// The job named by the path's first capture; 404 for a malformed or unknown id (no lookup for the former).
jobs::Job find_job(App& app, const httplib::Request& req);

/// Mesh files for the scene checks: a stored mesh is parsed once and its parsed form shared (MeshStore).
scene::MeshFiles mesh_files(App& app);

/// The whole file at `path`, nullopt when it cannot be opened.
std::optional<std::string> read_file(const std::filesystem::path& path);

/// 1 to `max_length` ASCII digits.
bool all_digits(const std::string& text, std::size_t max_length);

/// The `format` query parameter: `allowed[0]` when absent, 400 when not one of `allowed`.
std::string format_param(const httplib::Request& req, const std::vector<std::string>& allowed);

/// Streams a file from disk, honouring a single byte range (RFC 9110 §14: 206 with Content-Range, 416
/// with Content-Range: bytes */SIZE when unsatisfiable, lengths clamped to the file).
void stream_file(const httplib::Request& req, httplib::Response& res, const std::filesystem::path& path,
                 const std::string& type);

}  // namespace stoss::server::http
