#include "server/http/scene_check.hpp"

#include <string>

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
  if (n > 0)
    detail += ", the first: " + errors[0].value("pointer", "") + ": " + errors[0].value("message", "");
  return {422, "urn:stoss:problem:invalid-scene", "Invalid scene", detail, {{"errors", std::move(errors)}}};
}

}  // namespace

nlohmann::json parse_json_body(const httplib::Request& req, const Limits& limits) {
  if (req.body.size() > limits.max_body_bytes)
    throw ProblemError(Problem{
        413,
        "urn:stoss:problem:limit-exceeded",
        "Request body too large",
        "the body has " + std::to_string(req.body.size()) +
            " bytes, more than the server limit max_body_bytes = " + std::to_string(limits.max_body_bytes),
        {{"limits",
          {{{"name", "max_body_bytes"}, {"limit", limits.max_body_bytes}, {"value", req.body.size()}}}}}});
  try {
    return nlohmann::json::parse(req.body);
  } catch (const nlohmann::json::parse_error& e) {
    throw ProblemError(Problem{400,
                               "urn:stoss:problem:malformed-json",
                               "Malformed JSON",
                               "the body is not JSON: " + plain_message(e),
                               {{"byte", e.byte}}});
  } catch (const nlohmann::json::exception& e) {  // e.g. a number literal out of the range of double
    throw ProblemError(Problem{400, "urn:stoss:problem:malformed-json", "Malformed JSON",
                               "the body is not usable JSON: " + plain_message(e)});
  }
}

scene::Summary check_scene(const nlohmann::json& scene, const Limits& limits) {
  if (auto problem = check_scene_limits_early(scene, limits)) throw ProblemError(*problem);
  scene::Summary summary;
  try {
    summary = scene::summarize(scene::load(scene));
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
  if (auto problem = check_scene_limits(summary, limits)) throw ProblemError(*problem);
  return summary;
}

}  // namespace stoss::server::http
