// The run-time estimate (W7) of docs/scene.md, by its form only (never against a wall clock): it is
// t₀ plus steps times a per-step cost that grows as E^k with the elements, with the Courant number, and
// with the slave nodes, a frictional pair's twice, a mortar pair's 1.9 times.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/scene/estimates.hpp"
#include "core/scene/scene.hpp"

namespace stoss::scene {
namespace {

using nlohmann::json;

json seed() {
  std::ifstream in(std::string(STOSS_SOURCE_DIR) + "/api/examples/hollow_ball_plate.json");
  return json::parse(in);
}

double per_step(const json& scene) {
  const model::Model m = load(scene);
  return (estimate(m).wall_seconds - estimate_setup_seconds) / m.time.steps();
}

TEST(RunTimeEstimate, IsTheFormulaOfItsInputs) {
  const model::Model m = load(seed());
  const Estimates e = estimate(m);
  double courant = 0;
  for (const BodyScale& b : e.bodies) courant = std::max(courant, b.courant);
  // The seed: 100 steps, 944 elements, 218 slave nodes, no friction.
  EXPECT_DOUBLE_EQ(e.wall_seconds, run_seconds(100, 944, courant, 218));
  EXPECT_DOUBLE_EQ(
      run_seconds(100, 944, courant, 218),
      0.05 + 100 * (1e-5 * std::pow(944, 1.1) * (1 + 2 * std::log10(1 + courant)) + 1.7e-4 * 218));
}

TEST(RunTimeEstimate, ScalesWithTheSteps) {
  json longer = seed();
  longer["time"]["end"] = 3.0;  // 300 steps instead of 100
  const model::Model m = load(seed()), l = load(longer);
  EXPECT_NEAR(estimate(l).wall_seconds - estimate_setup_seconds,
              3 * (estimate(m).wall_seconds - estimate_setup_seconds), 1e-9);
  EXPECT_NEAR(per_step(longer), per_step(seed()), 1e-12);
}

TEST(RunTimeEstimate, GrowsFasterThanTheElementsAndWithTheCourantNumber) {
  const double one = run_seconds(1, 1000, 0, 0) - estimate_setup_seconds;
  EXPECT_NEAR(run_seconds(1, 2000, 0, 0) - estimate_setup_seconds, std::pow(2, 1.1) * one, 1e-12);
  EXPECT_NEAR(run_seconds(1, 1000, 99, 0) - estimate_setup_seconds, 5 * one, 1e-12);  // 1 + 2 log₁₀ 100
}

TEST(RunTimeEstimate, AFrictionalPairCountsItsSlaveNodesTwice) {
  json friction = seed();
  friction["contact"][0] = {
      {"slave", "ball/outer"}, {"master", "plate/top"}, {"enforcement", "penalty"}, {"friction", 0.2}};
  json frictionless = friction;
  frictionless["contact"][0]["friction"] = 0.0;
  EXPECT_NEAR(per_step(friction) - per_step(frictionless), estimate_slave_node_seconds * 218, 1e-12);
}

TEST(RunTimeEstimate, AMortarPairCountsItsSlaveNodesAsMeasured) {
  json mortar = seed();
  mortar["contact"][0]["discretization"] = "mortar";
  mortar["contact"][0].erase("switch_hysteresis");
  EXPECT_NEAR(per_step(mortar) - per_step(seed()),
              (estimate_mortar_weight - 1) * estimate_slave_node_seconds * 218, 1e-12);
}

}  // namespace
}  // namespace stoss::scene
