#pragma once
// Test helper: the issues a scene's validation reports, empty when it loads.
#include <vector>

#include "core/scene/scene.hpp"

namespace stoss::scene::testing {

inline std::vector<Issue> issues_of(const nlohmann::json& scene) {
  try {
    load(scene);
  } catch (const SceneError& e) {
    return e.issues;
  }
  return {};
}

}  // namespace stoss::scene::testing
