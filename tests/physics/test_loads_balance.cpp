// The system shall count the work of external loads (issue 23 §1, §4; docs/theory.md §5b): with
// energy–momentum, H − W stays constant within 1e-10 of max |H| per step and over the run, for a free block
// pushed by a traction ramp and for the seed's ball striking a plate that a pressure ramp pushes up
// (api/examples/ball_plate_pressure.json), and the block's momentum gain equals the traction's impulse.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../core/recording_observer.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"

namespace stoss {
namespace {

/// max_n |(H_{n+1} − W_{n+1}) − (H_n − W_n)| / max |H| over the recorded rows.
double worst_step_balance(const testing::RecordingObserver& r) {
  const auto H = r.series("total_energy"), W = r.series("external_work");
  double largest = 0, worst = 0;
  for (double h : H) largest = std::max(largest, std::abs(h));
  for (size_t n = 1; n < H.size(); ++n)
    worst = std::max(worst, std::abs((H[n] - W[n]) - (H[n - 1] - W[n - 1])));
  return worst / largest;
}

TEST(LoadsBalance, AFreeBlockUnderATractionRampKeepsHMinusWAndGainsTheImpulse) {
  // 1 × 1 × 1 block, traction (0, 0, 2) per unit area on its top, ramped 0 → 1 over [0, 0.5].
  const model::Model m = scene::load(nlohmann::json::parse(R"({
    "format": "stoss-scene/1", "name": "free block pushed by a traction ramp",
    "bodies": [ { "name": "block",
                  "mesh": { "box": { "min": [0, 0, 0], "max": [1, 1, 1], "divisions": [2, 2, 2] } },
                  "material": { "youngs_modulus": 100, "poisson_ratio": 0.3, "density": 1 } } ],
    "loads": [ { "surface": "block/top", "traction": [0, 0, 2], "amplitude": [[0, 0], [0.5, 1]] } ],
    "time": { "scheme": "energy_momentum", "step": 0.01, "end": 0.5 },
    "output": { "every": 10 } })"));
  EXPECT_TRUE(m.has_effect(model::effect::traction));
  testing::RecordingObserver r;
  const model::Summary s = simulate(m, r);
  ASSERT_TRUE(s.completed);
  EXPECT_LT(worst_step_balance(r), 1e-10);
  EXPECT_LT(s.energy_drift, 1e-10) << "max |H − W − H0| / max |H|";
  const auto W = r.series("external_work");
  EXPECT_EQ(W.front(), 0) << "row 0 is 0";
  EXPECT_GT(W.back(), 0) << "the traction pushes along the motion it causes";
  EXPECT_NEAR(s.external_work, W.back(), 1e-15);
  // Impulse: area 1 × 2 × ∫₀^0.5 (t/0.5) dt = 0.5; the midpoint amplitude integrates the ramp exactly.
  const double impulse = 0.5;
  EXPECT_NEAR(r.series("linear_momentum", 2).back(), impulse, 1e-10 * impulse);
  EXPECT_NEAR(r.series("linear_momentum", 0).back(), 0, 1e-10 * impulse);
  std::printf("block: |Δ(H − W)| ≤ %.1e max|H|, W = %.6f, L_z = %.12f (impulse 0.5)\n", worst_step_balance(r),
              W.back(), r.series("linear_momentum", 2).back());
}

TEST(LoadsBalance, TheSeedBallOnAPlatePushedByAPressureRampKeepsHMinusW) {
  const model::Model m =
      scene::load_file(std::string(STOSS_SOURCE_DIR) + "/api/examples/ball_plate_pressure.json");
  EXPECT_TRUE(m.has_effect(model::effect::pressure));
  testing::RecordingObserver r;
  const model::Summary s = simulate(m, r);
  ASSERT_TRUE(s.completed);
  EXPECT_LT(worst_step_balance(r), 1e-10) << "per step, through the impact";
  EXPECT_LT(s.energy_drift, 1e-10) << "over the run";
  const auto W = r.series("external_work");
  // The ball drives the plate down against the pressure: W < 0, and of the order of the energy moved.
  EXPECT_GT(std::abs(W.back()), 1e-2) << "the pressure does work on the plate";
  const auto active = r.series("active_contacts");
  EXPECT_GT(*std::max_element(active.begin(), active.end()), 0) << "the ball strikes the plate";
  EXPECT_EQ(s.verdict, "ok");
  std::printf("ball on pushed plate: |Δ(H − W)| ≤ %.1e max|H|, drift %.1e, W = %.4f\n", worst_step_balance(r),
              s.energy_drift, W.back());
}

}  // namespace
}  // namespace stoss
