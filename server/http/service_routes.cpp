#include "server/http/service_routes.hpp"

#include <filesystem>
#include <optional>
#include <string>

#include "core/scene/scene.hpp"
#include "core/scene/warnings.hpp"
#include "server/http/problem.hpp"
#include "server/http/route_support.hpp"
#include "server/http/scene_check.hpp"

namespace stoss::server::http {

namespace {

using httplib::Request;
using httplib::Response;

}  // namespace

void validate_scene(App& app, const Request& req, Response& res) {
  const nlohmann::json scene = parse_json_body(req, app.limits);
  const scene::Summary s = check_scene(scene, app.limits, mesh_files(app));
  nlohmann::json body = {{"valid", true},          {"effects", s.effects}, {"nodes", s.nodes},
                         {"elements", s.elements}, {"dofs", s.dofs},       {"steps", s.steps},
                         {"frames", s.frames}};
  body.update(scene::before_run_json(s));
  send_json(res, 200, body);
}

void get_schema(App&, const Request&, Response& res) {
  res.set_content(dump(scene::schema()), "application/schema+json");
}

void get_openapi(App&, const Request&, Response& res) {
  static const std::optional<std::string> text =
      read_file(std::filesystem::path(STOSS_SOURCE_DIR) / "api" / "openapi.yaml");
  if (!text) fail(500, "missing-file", "OpenAPI document missing", "api/openapi.yaml cannot be read");
  res.set_content(*text, "application/yaml");
}

void get_health(App&, const Request&, Response& res) {
  send_json(res, 200, {{"status", "ok"}});
}

void get_metrics(App& app, const Request&, Response& res) {
  res.set_content(app.metrics.render(app.store.count_by_status(), app.pool.running()),
                  "text/plain; version=0.0.4");
}

}  // namespace stoss::server::http
