#include "core/scene/scene.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>

#include "core/scene/build.hpp"
#include "core/scene/contact_merge.hpp"
#include "core/scene/held_check.hpp"
#include "core/scene/master_surface.hpp"
#include "core/scene/validate.hpp"
#include "core/scene/warnings.hpp"

namespace stoss::scene {

extern const char* const schema_text;

namespace {

std::string issue_lines(const std::vector<Issue>& issues) {
  std::string text;
  for (const Issue& i : issues)
    text += (text.empty() ? "" : "\n") + (i.pointer.empty() ? i.message : i.pointer + ": " + i.message);
  return text;
}

/// The parser's message without its "[json.exception.parse_error.101] " prefix.
std::string parse_message(const nlohmann::json::parse_error& e) {
  const std::string what = e.what();
  const size_t end_of_tag = what.find("] ");
  return what.rfind("[json.exception.", 0) == 0 && end_of_tag != std::string::npos
             ? what.substr(end_of_tag + 2)
             : what;
}

}  // namespace

SceneError::SceneError(std::vector<Issue> found)
    : std::runtime_error(issue_lines(found)), issues(std::move(found)) {}

model::Model load(const nlohmann::json& scene, const std::optional<std::filesystem::path>& mesh_directory) {
  return load(scene, MeshFiles{mesh_directory, {}, {}});
}

model::Model load(const nlohmann::json& scene, const MeshFiles& mesh_files) {
  nlohmann::json filled = scene;
  detail::Checker checker;
  checker.mesh_files = mesh_files;
  detail::check_scene(filled, checker);
  if (!checker.issues().empty()) throw SceneError(checker.issues());
  auto merged = detail::merge_contact_pairs(filled, checker);
  if (!checker.issues().empty()) throw SceneError(checker.issues());
  model::Model m = detail::build_model(filled, mesh_files);
  m.merged_contact = std::move(merged);
  detail::resolve_master_surfaces(m);
  if (auto unheld = detail::unheld_bodies(m); !unheld.empty()) throw SceneError(std::move(unheld));
  return m;
}

model::Model load_resolved(const nlohmann::json& resolved, const MeshFiles& mesh_files) {
  // Every resolved scene has these: validation fills them in when absent.
  const bool is_resolved = resolved.contains("time") && resolved["time"].contains("scheme") &&
                           resolved.contains("solver") && resolved["solver"].contains("tolerance") &&
                           resolved.contains("output") && resolved["output"].contains("every");
  if (!is_resolved) return load(resolved, mesh_files);
  model::Model m = detail::build_model(resolved, mesh_files);
  detail::resolve_master_surfaces(m);  // applies the stored master_surface and switch_gap of each pair
  return m;
}

model::Model load_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw SceneError({{"", "cannot read " + path + ": " + std::strerror(errno)}});
  nlohmann::json scene;
  try {
    scene = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw SceneError({{"", parse_message(e)}});
  }
  const std::filesystem::path directory = std::filesystem::path(path).parent_path();
  return load(scene, directory.empty() ? std::filesystem::path(".") : directory);
}

Summary summarize(const model::Model& model) {
  Summary s;
  s.effects = model.effects;
  s.nodes = model.mesh.node_count();
  s.elements = model.mesh.element_count();
  s.dofs = model.dof_count();
  s.ranks = model.solver.ranks;
  const model::TimeSpec& t = model.time;
  s.steps = static_cast<int>(std::min<long long>(
      model::step_bound(t.end, t.step, t.adaptive() ? std::optional(t.min_step) : std::nullopt,
                        model.output.interval),
      std::numeric_limits<int>::max()));
  s.frames = static_cast<int>(
      std::min<long long>(model.output.frame_count(s.steps, t.end), std::numeric_limits<int>::max()));
  s.estimates = estimate(model);
  s.warnings = warnings(model, s.estimates);
  s.choices = resolved_choices(model);
  return s;
}

nlohmann::json schema() {
  static const nlohmann::json parsed = nlohmann::json::parse(schema_text);
  return parsed;
}

}  // namespace stoss::scene
