// The system shall move supports by a prescribed displacement and report the force each support carries
// (issue 23 §2, §4; docs/theory.md §5b.7): a block pulled by a displacement ramp keeps, with energy–momentum,
// total_energy − external_work constant within 1e-10 of max |H| per step and over the run; a block at rest
// under gravity on a fixed bottom carries its weight on that bottom within 1e-10 relative.
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

model::Model pulled_block(const std::string& scheme) {
  // 1 × 1 × 1 block held on its bottom; its top is pulled up by 0.05 over [0, 0.2], then held there.
  return scene::load(nlohmann::json::parse(R"({
    "format": "stoss-scene/1", "name": "block pulled by its top",
    "bodies": [ { "name": "block",
                  "mesh": { "box": { "min": [0, 0, 0], "max": [1, 1, 1], "divisions": [2, 2, 2] } },
                  "material": { "youngs_modulus": 100, "poisson_ratio": 0.3, "density": 1 } } ],
    "boundary": [ { "surface": "block/bottom" },
                  { "surface": "block/top", "fix": "z", "displacement": [0, 0, 0.05],
                    "amplitude": [[0, 0], [0.2, 1]] } ],
    "time": { "scheme": ")" + scheme + R"(", "step": 0.01, "end": 0.4 },
    "solver": { "tolerance": 1e-12 },
    "output": { "every": 10 } })"));
}

TEST(PrescribedMotion, ABlockPulledByARampKeepsHMinusWWithEnergyMomentum) {
  const model::Model m = pulled_block("energy_momentum");
  EXPECT_TRUE(m.has_effect(model::effect::prescribed_motion));
  testing::RecordingObserver r;
  const model::Summary s = simulate(m, r);
  ASSERT_TRUE(s.completed);
  ASSERT_TRUE(r.has_series("reaction_force"));
  EXPECT_LT(worst_step_balance(r), 1e-10);
  EXPECT_LT(s.energy_drift, 1e-10) << "max |H − W − H0| / max |H|";
  const auto W = r.series("external_work");
  EXPECT_EQ(W.front(), 0) << "row 0 is 0";
  EXPECT_GT(W.back(), 0) << "the pull stretches the block: work flows in";
  // The top moved to z = 1.05 exactly and stays there (the first top node's z, from the last frame).
  const auto top_z = r.series("reaction_force", 3 + 2);
  EXPECT_EQ(top_z.front(), 0) << "row 0 is 0";
  EXPECT_GT(*std::max_element(top_z.begin(), top_z.end()), 0) << "the top support pulls the block up";
  std::printf("pulled block (EM): |Δ(H − W)| ≤ %.1e max|H|, drift %.1e, W = %.6f\n", worst_step_balance(r),
              s.energy_drift, W.back());
}

TEST(PrescribedMotion, ThePrescribedSurfaceEndsWhereTheAmplitudeSaysInEveryScheme) {
  for (const char* scheme : {"energy_momentum", "midpoint", "hht", "generalized_alpha", "static"}) {
    const model::Model m = pulled_block(scheme);
    testing::RecordingObserver r;
    ASSERT_TRUE(simulate(m, r).completed) << scheme;
    ASSERT_FALSE(r.frames.empty());
    const Eigen::VectorXd& x = r.frames.back().position;
    const std::vector<int> top = m.mesh.named_nodes("block/top");
    ASSERT_FALSE(top.empty());
    for (int I : top) EXPECT_NEAR(x[3 * I + 2], 1.05, 1e-14) << scheme << ": node " << I;
    const std::vector<int> bottom = m.mesh.named_nodes("block/bottom");
    for (int I : bottom) EXPECT_EQ(x[3 * I + 2], 0.0) << scheme;
    // The bottom holds the block down as hard as the top pulls it up, once the block is static.
    if (std::string(scheme) == "static") {
      const double top_force = r.series("reaction_force", 5).back(),
                   bottom_force = r.series("reaction_force", 2).back();
      EXPECT_GT(top_force, 0);
      EXPECT_NEAR(top_force + bottom_force, 0, 1e-9 * top_force);
    }
  }
}

// Static steps (time.scheme "static", issue 23 §3): the second step holds the load of the first, so the
// predictor already solves it and Newton measures it against the weight (docs/theory.md §5b.6).
TEST(PrescribedMotion, TheBottomOfABlockAtRestUnderGravityCarriesItsWeight) {
  // Static equilibrium under gravity (0, 0, −10): mass 2 × 1 × 1 × density 3 = 6, weight 60.
  const model::Model m = scene::load(nlohmann::json::parse(R"({
    "format": "stoss-scene/1", "name": "block at rest on its bottom",
    "bodies": [ { "name": "block",
                  "mesh": { "box": { "min": [0, 0, 0], "max": [2, 1, 1], "divisions": [2, 2, 2] } },
                  "material": { "youngs_modulus": 1000, "poisson_ratio": 0.3, "density": 3 } } ],
    "boundary": [ { "surface": "block/bottom" }, { "surface": "block/xmin", "fix": "x" } ],
    "gravity": [0, 0, -10],
    "time": { "scheme": "static", "step": 0.5, "end": 1 },
    "solver": { "tolerance": 1e-13 } })"));
  EXPECT_FALSE(m.has_effect(model::effect::prescribed_motion)) << "no displacement: today's support";
  testing::RecordingObserver r;
  ASSERT_TRUE(simulate(m, r).completed);
  ASSERT_TRUE(r.has_series("reaction_force"));
  const double weight = 60;
  const auto Fz = r.series("reaction_force", 2);
  EXPECT_EQ(Fz.front(), 0) << "row 0 is 0";
  EXPECT_NEAR(Fz.back(), weight, 1e-10 * weight);
  // Gravity has no x component: the supports' x forces balance (the bottom's and xmin's, which holds the
  // block's Poisson widening at x = 0 against the bottom's grip).
  EXPECT_NEAR(r.series("reaction_force", 0).back() + r.series("reaction_force", 3).back(), 0, 1e-10 * weight);
  // xmin's nodes on the bottom edge count in the first entry: xmin carries no vertical force.
  EXPECT_EQ(r.series("reaction_force", 3 + 2).back(), 0);
  EXPECT_FALSE(r.has_series("external_work")) << "no loads and no moving support";
  std::printf("block at rest: bottom reaction %.15f (weight 60)\n", Fz.back());
}

}  // namespace
}  // namespace stoss
