#pragma once
/// @file The routes of docs/api.md (api/openapi.yaml) on an httplib::Server.

#include <optional>
#include <string>
#include <vector>

#include "server/http/auth.hpp"
#include "server/http/connection_limit.hpp"
#include "server/http/httplib.hpp"
#include "server/http/limits.hpp"
#include "server/http/metrics.hpp"
#include "server/jobs/job_files.hpp"
#include "server/jobs/store.hpp"
#include "server/jobs/worker_pool.hpp"

namespace stoss::server::http {

/// What the routes work with.
struct App {
  jobs::JobStore& store;
  jobs::WorkerPool& pool;
  jobs::JobFiles files;
  Limits limits;
  std::optional<BearerAuth> auth;  ///< when set, every route but /healthz needs the token
  Metrics metrics;
};

/// One route of the API: its method, its path as api/openapi.yaml writes it ("/v1/jobs/{id}"), and
/// whether it needs the bearer token when the server has one.
struct RouteInfo {
  std::string method;
  std::string path;
  bool needs_token = true;
};

/// Every route install_routes registers (a test checks this against api/openapi.yaml).
std::vector<RouteInfo> routes();

/// The methods the API has for `path` ("GET", "POST", …), empty when no route matches the path.
std::vector<std::string> allowed_methods(const std::string& path);

/// Registers every route of the API. Handlers answer errors as problem+json.
void install_routes(httplib::Server& server, App& app);

/// Request hygiene before routing: a POST or DELETE without Content-Length and without Transfer-Encoding
/// has an empty body (RFC 9112 §6.3), as `curl -X POST …/cancel` sends it; cpp-httplib 0.11 would
/// otherwise wait for the client to close the connection. The declared Content-Type moves to
/// declared_type_header (cpp-httplib would parse and cap form bodies); a known path with a method it does
/// not have is answered 405 with Allow. With a `limit`, a connection over the per-client cap is answered
/// 503 before anything else (connection_limit.hpp; /healthz excepted).
///
/// Limits before reading: cpp-httplib 0.11 reads a body after this hook and before the handler, whole
/// into memory and with no cap for a chunked one. So this hook refuses, from the head alone, what must
/// not be read: an unknown route, a missing token (401), a Content-Length above max_body_bytes (413 with
/// the exact length), a chunked body on a route without a counting reader (411) and any other transfer
/// coding (501); such a connection is closed after the answer. The routes that take a body get a content
/// reader instead (install_routes), which counts the bytes as they arrive and stops at max_body_bytes
/// (413) or --request-timeout after the head (408). A request with `Expect: 100-continue` gets the same
/// refusals instead of the 100.
void install_request_defaults(httplib::Server& server, const App& app, ConnectionLimit* limit = nullptr);

/// The error handler (problem+json for statuses httplib sets itself: unknown route, oversize body, …),
/// the exception handler (catches everything, answers 500, never lets a request take the server down),
/// and the request counter of /metrics.
void install_error_handling(httplib::Server& server, Metrics& metrics, const Limits& limits = {});

}  // namespace stoss::server::http
