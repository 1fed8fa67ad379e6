#include "server/http/scene_check.hpp"

#include <algorithm>
#include <cctype>
#include <string>

#include "server/common/json_input.hpp"

namespace stoss::server::http {

namespace {

/// nlohmann's message without its "[json.exception.parse_error.101] " prefix.
std::string plain_message(const std::exception& e) {
  std::string text = e.what();
  if (!text.empty() && text.front() == '[') {
    const auto end = text.find("] ");
    if (end != std::string::npos) text.erase(0, end + 2);
  }
  return text;
}

Problem invalid_scene(nlohmann::json errors) {
  const std::size_t n = errors.size();
  std::string detail = n == 1 ? "the scene has 1 error" : "the scene has " + std::to_string(n) + " errors";
  if (n > 0) {
    const std::string pointer = errors[0].value("pointer", "");
    detail +=
        ", the first: " + (pointer.empty() ? "the scene " : pointer + ": ") + errors[0].value("message", "");
  }
  return {422, "urn:stoss:problem:invalid-scene", "Invalid scene", detail, {{"errors", std::move(errors)}}};
}

/// 422 at /solver/ranks when the scene asks for more MPI ranks than --max-ranks-per-job: no worker of this
/// service would ever claim it.
void check_ranks(const scene::Summary& summary, const Limits& limits) {
  if (summary.ranks <= limits.max_ranks_per_job) return;
  const std::string limit = std::to_string(limits.max_ranks_per_job);
  throw ProblemError(invalid_scene(nlohmann::json::array(
      {{{"pointer", "/solver/ranks"},
        {"message", "must be at most " + limit + " on this service (stoss serve --max-ranks-per-job " +
                        limit + "), got " + std::to_string(summary.ranks)}}})));
}

}  // namespace

std::string declared_content_type(const httplib::Request& req) {
  std::string type = req.has_header(declared_type_header) ? req.get_header_value(declared_type_header)
                                                          : req.get_header_value("Content-Type");
  type = type.substr(0, type.find(';'));
  while (!type.empty() && (type.back() == ' ' || type.back() == '\t')) type.pop_back();
  std::transform(type.begin(), type.end(), type.begin(), [](unsigned char c) { return std::tolower(c); });
  return type;
}

Problem body_too_large(std::size_t limit, std::optional<unsigned long long> value) {
  nlohmann::json entry = {{"name", "max_body_bytes"}, {"limit", limit}};
  std::string detail = "the request body exceeds the server limit max_body_bytes = " + std::to_string(limit);
  if (value) {
    entry["value"] = *value;
    detail = "the body has " + std::to_string(*value) +
             " bytes, more than the server limit max_body_bytes = " + std::to_string(limit);
  }
  return {413,
          "urn:stoss:problem:limit-exceeded",
          "Request body too large",
          detail,
          {{"limits", nlohmann::json::array({entry})}}};
}

nlohmann::json parse_json_body(const httplib::Request& req, const Limits& limits) {
  if (req.body.size() > limits.max_body_bytes)
    throw ProblemError(body_too_large(limits.max_body_bytes, req.body.size()));
  const std::string type = declared_content_type(req);
  const bool declared_json = type == "application/json" || type == "text/json" ||
                             (type.size() > 5 && type.compare(type.size() - 5, 5, "+json") == 0);
  // JSON is accepted whatever the Content-Type says (curl sends application/x-www-form-urlencoded by
  // default); a body that is not JSON and not declared as JSON is of a type no route takes.
  if (!declared_json && !looks_like_json(req.body))
    throw ProblemError(Problem{415,
                               "urn:stoss:problem:unsupported-media-type",
                               "Unsupported Media Type",
                               "the body is not JSON" +
                                   (type.empty() ? std::string() : " (Content-Type " + type + ")") +
                                   "; this route takes application/json",
                               {{"expected", nlohmann::json::array({"application/json"})}}});
  try {
    return parse_json_input(req.body);
  } catch (const JsonInputError& e) {
    if (e.kind == JsonInputError::Kind::too_deep)
      throw ProblemError(Problem{
          400,
          "urn:stoss:problem:too-deep",
          "JSON nested too deeply",
          std::string("the body is not usable JSON: ") + e.what(),
          {{"limits", nlohmann::json::array({{{"name", "max_json_depth"}, {"limit", max_json_depth}}})},
           {"byte", e.byte.value_or(0)}}});
    Problem p{400, "urn:stoss:problem:malformed-json", "Malformed JSON",
              std::string(e.byte ? "the body is not JSON: " : "the body is not usable JSON: ") + e.what()};
    if (e.byte) p.extra["byte"] = *e.byte;
    throw ProblemError(p);
  }
}

scene::Summary check_scene(const nlohmann::json& scene, const Limits& limits,
                           const scene::MeshFiles& mesh_files, nlohmann::json* resolved) {
  if (auto problem = check_scene_limits_early(scene, limits)) throw ProblemError(*problem);
  scene::Summary summary;
  try {
    model::Model model = scene::load(scene, mesh_files);
    summary = scene::summarize(model);
    if (resolved) *resolved = std::move(model.scene);
  } catch (const scene::SceneError& e) {
    nlohmann::json errors = nlohmann::json::array();
    for (const auto& issue : e.issues)
      errors.push_back({{"pointer", issue.pointer}, {"message", issue.message}});
    if (errors.empty()) errors.push_back({{"pointer", ""}, {"message", e.what()}});
    throw ProblemError(invalid_scene(std::move(errors)));
  } catch (const std::exception& e) {
    // A scene that passes validation but cannot be built (e.g. a degenerate imported mesh) is still a bad
    // scene.
    throw ProblemError(
        invalid_scene(nlohmann::json::array({{{"pointer", ""}, {"message", plain_message(e)}}})));
  }
  check_ranks(summary, limits);
  if (auto problem = check_scene_limits(summary, limits)) throw ProblemError(*problem);
  return summary;
}

}  // namespace stoss::server::http
