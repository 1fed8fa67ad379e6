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

void resolve_master_surfaces(model::Model& m) {
  std::vector<Issue> issues;
  for (size_t i = 0; i < m.contact.size(); ++i) {
    model::ContactPair& p = m.contact[i];
    nlohmann::json& e = m.scene["contact"][i];
    const auto why_not = smooth_unavailable(m, p);
    if (e.contains("master_surface") && e["master_surface"] == "smooth" && why_not) {
      issues.push_back({"/contact/" + std::to_string(i) + "/master_surface", *why_not});
      continue;
    }
    const bool smooth = !why_not && e.value("master_surface", "smooth") == "smooth";
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
