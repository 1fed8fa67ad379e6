#include "core/scene/master_surface.hpp"

#include <optional>
#include <vector>

#include "core/contact/geometry/smooth_surface.hpp"
#include "core/scene/scene.hpp"

namespace stoss::scene::detail {

std::optional<std::string> smooth_unavailable(const model::Model& m, const model::ContactPair& p) {
  const contact::SmoothSurface s = contact::smooth_surface(m.mesh.surface(p.master));
  if (!s.ok()) return "master " + p.master + " cannot carry a smooth surface: " + s.problem;
  return std::nullopt;
}

std::vector<int> written_contact_indices(const model::Model& m) {
  size_t written = m.contact.size();
  for (const model::Model::MergedPairs& merge : m.merged_contact) written += merge.written.size() - 1;
  std::vector<char> absorbed(written, 0);  // pairs as written that joined an earlier one
  for (const model::Model::MergedPairs& merge : m.merged_contact)
    for (size_t k = 1; k < merge.written.size(); ++k) absorbed[merge.written[k]] = 1;
  std::vector<int> out;
  for (size_t j = 0; j < written; ++j)
    if (!absorbed[j]) out.push_back(static_cast<int>(j));
  return out;
}

void resolve_master_surfaces(model::Model& m) {
  std::vector<Issue> issues;
  const std::vector<int> written = written_contact_indices(m);
  for (size_t i = 0; i < m.contact.size(); ++i) {
    model::ContactPair& p = m.contact[i];
    nlohmann::json& e = m.scene["contact"][i];
    // Mortar integrates on the faceted surface (docs/theory.md §4.7); validation refused "smooth" with it.
    const bool mortar = p.discretization == model::Discretization::mortar;
    const auto why_not = mortar ? std::nullopt : smooth_unavailable(m, p);
    if (e.contains("master_surface") && e["master_surface"] == "smooth" && why_not) {
      issues.push_back({"/contact/" + std::to_string(written[i]) + "/master_surface", *why_not});
      continue;
    }
    const bool smooth = !mortar && !why_not && e.value("master_surface", "smooth") == "smooth";
    p.master_surface = smooth ? model::MasterSurface::smooth : model::MasterSurface::faceted;
    e["master_surface"] = smooth ? "smooth" : "faceted";
    if (!e.contains("switch_gap")) {
      p.switch_gap = smooth ? model::SwitchGap::keep : model::SwitchGap::clamp;
      e["switch_gap"] = smooth ? "keep" : "clamp";
    }
  }
  if (!issues.empty()) throw SceneError(issues);
}

}  // namespace stoss::scene::detail
