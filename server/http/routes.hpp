#pragma once
/// @file The routes of docs/api.md (api/openapi.yaml) on an httplib::Server.

#include <optional>
#include <string>
#include <vector>

#include "server/http/auth.hpp"
#include "server/http/httplib.hpp"
#include "server/http/limits.hpp"
#include "server/http/metrics.hpp"
#include "server/jobs/job_files.hpp"
#include "server/jobs/running/worker_pool.hpp"
#include "server/jobs/store/store.hpp"

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

/// Registers every route of the API, each behind the request gate (request_gate.hpp: guarded, reading).
/// Handlers answer errors as problem+json.
void install_routes(httplib::Server& server, App& app);

/// The route a request goes to (HEAD goes where GET does), or nullptr (request_gate.hpp refuses it).
const RouteInfo* find_route(const httplib::Request& req);

}  // namespace stoss::server::http
