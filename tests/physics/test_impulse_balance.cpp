// Where a system is not free, its momentum changes by the impulse of the loads, gravity and the supports
// (docs/results.md (V10)): the verdict's impulse_balance check, here recomputed from the result's series.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../core/recording_observer.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"

namespace stoss {
namespace {

const model::Check* find_check(const model::Summary& s, const std::string& name) {
  for (const model::Check& c : s.checks)
    if (c.name == name) return &c;
  return nullptr;
}

/// A 1 × 1 × 1 block (mass 1) held at its bottom, dropped into gravity (0, 0, −10): it rings on its support.
model::Model held_block(const std::string& scheme) {
  return scene::load(nlohmann::json::parse(R"({
    "format": "stoss-scene/1", "name": "block held at its bottom under gravity",
    "bodies": [ { "name": "block",
                  "mesh": { "box": { "min": [0, 0, 0], "max": [1, 1, 1], "divisions": [2, 2, 2] } },
                  "material": { "youngs_modulus": 1000, "poisson_ratio": 0.3, "density": 1 },
                  "initial_velocity": [0.5, 0, 0] } ],
    "boundary": [ { "surface": "block/bottom", "fix": "xyz" } ],
    "gravity": [0, 0, -10],
    "time": { "scheme": ")" + scheme + R"(", "step": 0.01, "end": 0.3 } })"));
}

TEST(ImpulseBalance, AHeldBlockUnderGravityGainsWhatGravityAndItsSupportGive) {
  const model::Model m = held_block("energy_momentum");
  testing::RecordingObserver r;
  const model::Summary s = simulate(m, r);
  ASSERT_TRUE(s.completed);
  EXPECT_EQ(find_check(s, "linear_momentum_drift"), nullptr) << "momentum is not kept where it is held";
  const model::Check* check = find_check(s, "impulse_balance");
  ASSERT_NE(check, nullptr);
  EXPECT_TRUE(check->passed);
  EXPECT_LT(check->value, 1e-10);
  // The same balance from the series: Δp_n = h_n (m g + R_n), with and without the support's force.
  const auto h = r.series("step_size");
  double worst = 0, without_support = 0, largest = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const auto p = r.series("linear_momentum", axis), R = r.series("reaction_force", axis);
    const double g = axis == 2 ? -10.0 : 0.0;
    for (size_t n = 1; n < p.size(); ++n) {
      worst = std::max(worst, std::abs(p[n] - p[n - 1] - h[n] * (g + R[n])));
      without_support = std::max(without_support, std::abs(p[n] - p[n - 1] - h[n] * g));
      largest = std::max(largest, std::abs(h[n] * R[n]));
    }
  }
  EXPECT_LT(worst, 1e-10) << "the series close the balance step by step (momenta of order 0.5)";
  EXPECT_GT(without_support, 1e-3)
      << "the support's impulse is no round-off: leaving it out breaks the balance";
  EXPECT_GT(largest, 0.05) << "the support carries the block (m g h = 0.1 per step)";
}

TEST(ImpulseBalance, IsCheckedForMidpointTypeSchemesOnly) {
  for (const char* scheme : {"midpoint", "energy_momentum"}) {
    testing::RecordingObserver r;
    const model::Summary s = simulate(held_block(scheme), r);
    const model::Check* check = find_check(s, "impulse_balance");
    ASSERT_NE(check, nullptr) << scheme;
    EXPECT_LT(check->value, 1e-10) << scheme;
  }
  // HHT-α's momentum follows its weighted accelerations, not the step's force at one point in time.
  testing::RecordingObserver r;
  EXPECT_EQ(find_check(simulate(held_block("hht"), r), "impulse_balance"), nullptr);
}

}  // namespace
}  // namespace stoss
