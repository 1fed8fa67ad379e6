// Issue 24 §2: with energy_momentum, frictionless mortar contact does no work in a persistent step. The
// seed's example (api/examples/hollow_ball_plate.json) with "discretization": "mortar": the pair's force is
// the discrete gradient of each face pair's weighted gaps (docs/theory.md §4.7.2), a node activates with its
// gap frozen where it was (4.83), so every step keeps energy to 1e-10 H0 through the impact, the patch's
// growth and shrinking (slave faces start and stop overlapping master faces, nodes activate and release) and
// the late activation at t = 0.93 that gained 0.43 H0 in the midpoint form; both momenta to 1e-10.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "../core/recording_observer.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"

namespace stoss {
namespace {

using testing::RecordingObserver;

const RecordingObserver& seed_with_mortar() {
  static const RecordingObserver run = [] {
    std::ifstream in(std::string(STOSS_SOURCE_DIR) + "/api/examples/hollow_ball_plate.json");
    nlohmann::json scene = nlohmann::json::parse(in);
    scene["contact"][0]["discretization"] = "mortar";
    scene["contact"][0].erase("switch_hysteresis");  // a node-to-segment setting
    const model::Model m = scene::load(scene);
    EXPECT_EQ(m.contact.at(0).discretization, model::Discretization::mortar);
    EXPECT_EQ(m.time.scheme, model::Scheme::energy_momentum);
    RecordingObserver r;
    simulate(m, r);
    return r;
  }();
  return run;
}

TEST(MortarEnergyMomentum, TheSeedExampleKeepsEnergyInEveryStepAndBothMomenta) {
  const RecordingObserver& r = seed_with_mortar();
  ASSERT_TRUE(r.summary.completed);
  ASSERT_EQ(r.summary.steps, 100);
  const auto H = r.series("total_energy"), jump = r.series("contact_energy_jump");
  const auto active = r.series("active_contacts");
  double worst_step = 0, worst_jump = 0;
  int changes_of_the_active_set = 0;
  for (size_t n = 1; n < H.size(); ++n) {
    worst_step = std::max(worst_step, std::abs(H[n] - H[n - 1]) / H[0]);
    worst_jump = std::max(worst_jump, std::abs(jump[n]) / H[0]);
    changes_of_the_active_set += active[n] != active[n - 1];
  }
  std::printf(
      "seed with mortar (EM): max |ΔH|/H0 per step %.1e, drift %.1e, max jump %.1e H0, active-set changes "
      "%d, "
      "momentum drifts %.1e / %.1e, Newton its/step %.2f\n",
      worst_step, r.summary.energy_drift, worst_jump, changes_of_the_active_set,
      r.vector_drift("linear_momentum"), r.vector_drift("angular_momentum"),
      r.summary.newton_iterations_per_step);
  EXPECT_LT(worst_step, 1e-10) << "every step: impact, patch growth, releases, the activation at t = 0.93";
  EXPECT_LT(r.summary.energy_drift, 1e-10);
  EXPECT_LT(worst_jump, 1e-12) << "contact_energy_jump: activations freeze the gap they start with";
  EXPECT_GE(changes_of_the_active_set, 4) << "activations and releases inside the run";
  EXPECT_LT(r.vector_drift("linear_momentum"), 1e-10);
  EXPECT_LT(r.vector_drift("angular_momentum"), 1e-10);
  const auto [first, last] = r.contact_window();
  EXPECT_NEAR(first, 0.31, 0.015) << "the ball reaches the plate when node-to-segment says it does";
  // In contact for more than 0.3 at a sideways speed of 1 (its momentum over its mass): the ball's faces
  // slide over more than one plate face (0.25), so face pairs start and stop overlapping.
  EXPECT_GT(last - first, 0.3);
}

}  // namespace
}  // namespace stoss
