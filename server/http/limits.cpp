#include "server/http/limits.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace stoss::server::http {

namespace {

double number_at(const nlohmann::json& j, const char* key) {
  if (!j.is_object()) return 0;
  auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : 0.0;
}

/// Nodes a mesh description will produce, from its parameters: exact for generators (a box has
/// Π (divisions + 1), a hollow sphere (6 d² + 2)(layers + 1): each node layer is the cube-sphere's surface
/// grid of docs/theory.md §7) and inline meshes; 0 for mesh files, counted when read.
double estimated_nodes(const nlohmann::json& mesh) {
  if (!mesh.is_object()) return 0;
  if (auto box = mesh.find("box"); box != mesh.end() && box->is_object()) {
    auto d = box->find("divisions");
    if (d == box->end() || !d->is_array()) return 0;
    double n = 1;
    for (const auto& di : *d) n *= di.is_number() ? di.get<double>() + 1 : 1;
    return n;
  }
  if (auto sphere = mesh.find("hollow_sphere"); sphere != mesh.end()) {
    const double d = number_at(*sphere, "divisions"), layers = number_at(*sphere, "layers");
    return (6 * d * d + 2) * (layers + 1);
  }
  if (auto nodes = mesh.find("nodes"); nodes != mesh.end() && nodes->is_array())
    return static_cast<double>(nodes->size());
  return 0;
}

/// Scene-level numbers as the later model would report them, computed from the JSON alone.
scene::Summary estimated_summary(const nlohmann::json& scene) {
  double nodes = 0, steps = 0, every = 1;
  if (!scene.is_object()) return {};
  if (auto bodies = scene.find("bodies"); bodies != scene.end() && bodies->is_array())
    for (const auto& body : *bodies)
      if (body.is_object() && body.contains("mesh")) nodes += estimated_nodes(body["mesh"]);
  if (auto time = scene.find("time"); time != scene.end()) {
    const double step = number_at(*time, "step"), end = number_at(*time, "end");
    if (step > 0 && end > 0) steps = end / step;
  }
  if (auto output = scene.find("output"); output != scene.end() && number_at(*output, "every") >= 1)
    every = number_at(*output, "every");
  auto clamp = [](double x) { return static_cast<int>(std::min(x, 2e9)); };
  scene::Summary s;
  s.nodes = clamp(nodes);
  s.steps = clamp(std::floor(steps));
  s.frames = clamp(std::floor(steps / every));
  return s;
}

}  // namespace

std::optional<Problem> check_scene_limits_early(const nlohmann::json& scene, const Limits& limits) {
  // Generated and inline meshes are counted exactly before anything is built: a sphere over max_nodes is
  // refused without generating it.
  return check_scene_limits(estimated_summary(scene), limits);
}

std::optional<Problem> check_scene_limits(const scene::Summary& scene, const Limits& limits) {
  nlohmann::json exceeded = nlohmann::json::array();
  std::string detail;
  auto check = [&](const char* name, long long value, long long limit, const char* what) {
    if (value <= limit) return;
    exceeded.push_back({{"name", name}, {"limit", limit}, {"value", value}});
    if (!detail.empty()) detail += "; ";
    detail += std::string("the scene has ") + std::to_string(value) + " " + what +
              ", more than the server limit " + name + " = " + std::to_string(limit);
  };
  check("max_nodes", scene.nodes, limits.max_nodes, "nodes");
  check("max_steps", scene.steps, limits.max_steps, "time steps");
  check("max_frames", scene.frames, limits.max_frames, "output frames");
  if (exceeded.empty()) return std::nullopt;
  return Problem{413,
                 "urn:stoss:problem:limit-exceeded",
                 "Scene exceeds a server limit",
                 detail,
                 {{"limits", exceeded}}};
}

}  // namespace stoss::server::http
