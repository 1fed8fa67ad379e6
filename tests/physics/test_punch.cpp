// A flat punch pressed into a block (issue 23 §6, api/examples/punch.json; docs/measurements.md "A punch's
// force–displacement curve"): a stiff punch whose top moves down by prescribed motion, static load steps.
// - At every load level the punch's support, the contact and the block's bottom balance: the support's
//   reaction_force on the punch equals the contact force the punch exerts on the block, and the block's
//   bottom carries it, within 1e-8 of the final force: the steps are solved to the tolerance 1e-10 of the
//   force scale (5b.7a), which the stiff punch makes ≈ 5 (docs/theory.md (5b.10), (5b.12); measured
//   ≤ 1.5e-9 of it).
// - Between equilibria the supports' work is the trapezoid rule (5b.7b): W − ΔV is O(Δδ³) per step, so
//   |H − W| / H at the end falls by 4 per halving of the load step (the test asks 3.6–4.4), and on 10 steps
//   stays below 1e-3 (measured 3.5e-4). The end-point rule it replaced was first order: 9.6 % on 10 steps.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "../core/recording_observer.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"

namespace stoss {
namespace {

const std::string example = std::string(STOSS_SOURCE_DIR) + "/api/examples/punch.json";

/// The example on the coarser block of 8 × 8 × 4 elements with the given load step.
model::Model coarse_punch(double step) {
  nlohmann::json scene = nlohmann::json::parse(std::ifstream(example));
  scene["bodies"][0]["mesh"]["box"]["divisions"] = {8, 8, 4};
  scene["time"]["step"] = step;
  return scene::load(scene);
}

/// |H − W| / H at the end of the run.
double energy_work_gap(const testing::RecordingObserver& r) {
  const double H = r.series("total_energy").back(), W = r.series("external_work").back();
  return std::abs(H - W) / H;
}

TEST(Punch, TheSupportTheContactAndTheBottomBalanceAtEveryLoadLevel) {
  testing::RecordingObserver r;
  const model::Summary s = simulate(scene::load_file(example), r);
  ASSERT_TRUE(s.completed);
  const auto contact = r.series("contact_force", 2);
  const auto bottom = r.series("reaction_force", 2), punch_top = r.series("reaction_force", 3 + 2);
  ASSERT_EQ(contact.size(), 11u);
  EXPECT_LT(contact.back(), -1) << "the punch pushes the block down";
  const double bound = 1e-8 * std::abs(contact.back());
  for (size_t n = 1; n < contact.size(); ++n) {
    EXPECT_NEAR(punch_top[n], contact[n], bound) << "load level " << n;
    EXPECT_NEAR(bottom[n], -contact[n], bound) << "load level " << n;
    if (n > 1) EXPECT_LT(contact[n], contact[n - 1]) << "the force grows with the indentation";
  }
  std::printf("punch: F(δ = 0.05) = %.6f, W = %.6e, H = %.6e\n", -contact.back(),
              r.series("external_work").back(), r.series("total_energy").back());
}

TEST(Punch, TheSupportsWorkMatchesTheStrainEnergyToSecondOrderInTheLoadStep) {
  double gap[2];
  for (int k = 0; k < 2; ++k) {
    testing::RecordingObserver r;
    ASSERT_TRUE(simulate(coarse_punch(k == 0 ? 0.1 : 0.05), r).completed);
    gap[k] = energy_work_gap(r);
  }
  EXPECT_LT(gap[0], 1e-3) << "|H − W| / H on 10 load steps";
  EXPECT_GT(gap[0] / gap[1], 3.6);
  EXPECT_LT(gap[0] / gap[1], 4.4);
  std::printf("punch: |H − W| / H = %.3e (10 steps), %.3e (20 steps), ratio %.2f\n", gap[0], gap[1],
              gap[0] / gap[1]);
}

}  // namespace
}  // namespace stoss
