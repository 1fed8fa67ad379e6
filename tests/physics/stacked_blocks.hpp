#pragma once
// Test helper: two 1 × 1 × 0.5 blocks stacked, `lower` on z ∈ [0, 0.5] and `upper` on [0.5, 1] (E = 1000,
// ν = 0.3, ρ = 1), shared by the contact-force, static-step and patch-under-pressure tests.
#include <nlohmann/json.hpp>
#include <string>

namespace stoss::testing {

/// The scene entry of one block: n × n divisions in x and y, `layers` in z, its bottom at z0.
inline nlohmann::json stacked_block(const char* name, double z0, int n, int layers) {
  const nlohmann::json material = {{"youngs_modulus", 1000}, {"poisson_ratio", 0.3}, {"density", 1}};
  return {
      {"name", name},
      {"mesh", {{"box", {{"min", {0, 0, z0}}, {"max", {1, 1, z0 + 0.5}}, {"divisions", {n, n, layers}}}}}},
      {"material", material}};
}

/// Both blocks on rollers: lower/bottom holds z, xmin holds x and ymin holds y on both (entries in that
/// order: lower/bottom, lower/xmin, lower/ymin, upper/xmin, upper/ymin), so the exact interface pressure
/// under a uniform load is uniform for any ν.
inline nlohmann::json roller_boundary() {
  nlohmann::json boundary = nlohmann::json::array({{{"surface", "lower/bottom"}, {"fix", "z"}}});
  for (const std::string body : {"lower", "upper"}) {
    boundary.push_back({{"surface", body + "/xmin"}, {"fix", "x"}});
    boundary.push_back({{"surface", body + "/ymin"}, {"fix", "y"}});
  }
  return boundary;
}

}  // namespace stoss::testing
