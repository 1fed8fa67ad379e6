#include "server/http/page_routes.hpp"

#include <string>

#include "server/http/route_support.hpp"
#include "server/web/assets.hpp"

namespace stoss::server::http {

namespace {

using httplib::Request;
using httplib::Response;

/// Whether some body of `scene` names a mesh file (the service refuses those: it reads no files).
bool names_mesh_file(const nlohmann::json& scene) {
  for (const auto& body : scene.value("bodies", nlohmann::json::array()))
    if (body.is_object() && body.value("mesh", nlohmann::json::object()).contains("file")) return true;
  return false;
}

}  // namespace

void get_page(App&, const Request&, Response& res) {
  const auto page = web::find_asset("index.html");
  if (!page) fail(500, "internal", "Page missing", "index.html was not compiled in");
  res.set_header("Cache-Control", "no-cache");
  res.set_content(std::string(page->bytes), std::string(page->media_type));
}

void get_asset(App&, const Request& req, Response& res) {
  const std::string name = req.matches[1].str();
  const auto asset = web::find_asset(name);
  if (!asset) fail(404, "no-route", "Not Found", "the page has no file " + name.substr(0, 100));
  res.set_header("Cache-Control", "no-cache");
  res.set_content(std::string(asset->bytes), std::string(asset->media_type));
}

void list_examples(App&, const Request&, Response& res) {
  static const nlohmann::json examples = [] {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& file : web::embedded_examples()) {
      const nlohmann::json scene = nlohmann::json::parse(file.bytes);
      if (names_mesh_file(scene)) continue;
      const std::string name(file.name.substr(0, file.name.rfind(".json")));
      list.push_back({{"name", name}, {"title", scene.value("name", name)}, {"scene", scene}});
    }
    return nlohmann::json{{"examples", list}};
  }();
  send_json(res, 200, examples);
}

}  // namespace stoss::server::http
