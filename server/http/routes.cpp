#include "server/http/routes.hpp"

#include <algorithm>
#include <regex>

#include "server/http/job_file_routes.hpp"
#include "server/http/job_routes.hpp"
#include "server/http/mesh_routes.hpp"
#include "server/http/page_routes.hpp"
#include "server/http/request_gate.hpp"
#include "server/http/service_routes.hpp"

namespace stoss::server::http {

namespace {

using httplib::Request;
using Route = RouteHandler;

struct RouteEntry {
  RouteInfo info;
  Route handler;
};

/// The API: every route, as api/openapi.yaml names it.
const std::vector<RouteEntry>& route_table() {
  static const std::vector<RouteEntry> table = {
      {{"POST", "/v1/jobs", true}, submit_job},
      {{"GET", "/v1/jobs", true}, list_jobs},
      {{"GET", "/v1/jobs/{id}", true}, get_job},
      {{"DELETE", "/v1/jobs/{id}", true}, delete_job},
      {{"POST", "/v1/jobs/{id}/cancel", true}, cancel_job},
      {{"GET", "/v1/jobs/{id}/result", true}, get_result},
      {{"GET", "/v1/jobs/{id}/result.xdmf", true}, get_result_xdmf},
      {{"GET", "/v1/jobs/{id}/result_mesh.xdmf", true}, get_result_mesh_xdmf},
      {{"GET", "/v1/jobs/{id}/series", true}, get_series},
      {{"GET", "/v1/jobs/{id}/log", true}, get_log},
      {{"GET", "/v1/jobs/{id}/study", true}, get_study},
      {{"POST", "/v1/studies", true}, submit_study},
      {{"POST", "/v1/validate", true}, validate_scene},
      {{"POST", "/v1/meshes", true}, post_mesh},
      {{"GET", "/v1/meshes/{id}", true}, get_mesh},
      {{"DELETE", "/v1/meshes/{id}", true}, delete_mesh},
      {{"GET", "/v1/schema/scene", true}, get_schema},
      {{"GET", "/v1/jobs/{id}/scene", true}, get_scene},
      {{"GET", "/v1/openapi.yaml", true}, get_openapi},
      {{"GET", "/v1/examples", true}, list_examples},
      {{"GET", "/", false}, get_page},
      {{"GET", "/web/{asset}", false}, get_asset},
      {{"GET", "/healthz", false}, get_health},
      {{"GET", "/metrics", true}, get_metrics},
  };
  return table;
}

/// The httplib pattern of an OpenAPI path: a parameter ("{id}", "{asset}") captures one segment, "." is
/// literal.
std::string pattern_of(const std::string& path) {
  std::string pattern;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (path[i] == '{' && path.find('}', i) != std::string::npos) {
      pattern += "([^/]+)";
      i = path.find('}', i);
    } else {
      if (path[i] == '.') pattern += '\\';
      pattern += path[i];
    }
  }
  return pattern;
}

/// Every route with its compiled path pattern.
const std::vector<std::pair<std::regex, const RouteInfo*>>& route_patterns() {
  static const std::vector<std::pair<std::regex, const RouteInfo*>> patterns = [] {
    std::vector<std::pair<std::regex, const RouteInfo*>> out;
    for (const auto& r : route_table()) out.emplace_back(std::regex(pattern_of(r.info.path)), &r.info);
    return out;
  }();
  return patterns;
}

}  // namespace

const RouteInfo* find_route(const Request& req) {
  if (req.path.size() > 1024) return nullptr;
  const std::string method = req.method == "HEAD" ? "GET" : req.method;
  for (const auto& [pattern, info] : route_patterns())
    if (info->method == method && std::regex_match(req.path, pattern)) return info;
  return nullptr;
}

std::vector<std::string> allowed_methods(const std::string& path) {
  std::vector<std::string> methods;
  if (path.size() > 1024) return methods;
  for (const auto& [pattern, info] : route_patterns())
    if (std::regex_match(path, pattern) &&
        std::find(methods.begin(), methods.end(), info->method) == methods.end())
      methods.push_back(info->method);
  return methods;
}

std::vector<RouteInfo> routes() {
  std::vector<RouteInfo> out;
  for (const auto& r : route_table()) out.push_back(r.info);
  return out;
}

void install_routes(httplib::Server& server, App& app) {
  for (const auto& [info, handler] : route_table()) {
    const std::string pattern = pattern_of(info.path);
    auto guarded_handler = guarded(app, handler, info.needs_token);
    if (info.method == "GET") server.Get(pattern, guarded_handler);
    if (info.method == "POST") server.Post(pattern, reading(app, handler, info.needs_token));
    if (info.method == "DELETE") server.Delete(pattern, guarded_handler);
  }
}

}  // namespace stoss::server::http
