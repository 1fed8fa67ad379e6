// No silent seams (issue 23 §5; docs/scene.md "Pairs that share a slave"): api/examples/ball_on_box_edge.json
// writes a ball striking a box's edge as two pairs, ball/outer → box/top and ball/outer → box/xmax. Loading
// merges them into one pair with the union master, and the energy–momentum run keeps |H_n − H_0| within
// 1e-10 of max |H| in every step with every slave node projected. Kept apart by hand (the comparator), the
// two pairs leave slave nodes unprojected at the edge and the oblique impact gains energy (measured: 101
// nodes, an energy error of 1.7 max |H|).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "../core/recording_observer.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"

namespace stoss {
namespace {

const std::string example = std::string(STOSS_SOURCE_DIR) + "/api/examples/ball_on_box_edge.json";

TEST(BallOnBoxEdge, TheExampleIsWrittenAsTwoPairsAndLoadsAsOneWithTheUnionMaster) {
  const nlohmann::json written = nlohmann::json::parse(std::ifstream(example));
  ASSERT_EQ(written["contact"].size(), 2u);
  EXPECT_EQ(written["contact"][0]["master"], "box/top");
  EXPECT_EQ(written["contact"][1]["master"], "box/xmax");
  const model::Model m = scene::load_file(example);
  ASSERT_EQ(m.contact.size(), 1u);
  EXPECT_EQ(m.contact[0].master, "box/top+xmax");
  EXPECT_EQ(m.contact[0].master_surface, model::MasterSurface::smooth);
}

/// The run's energy and momentum bounds across the edge, and (`projects`: node-to-segment) every slave node
/// projected; prints `label`.
void expect_energy_across_the_edge(const model::Model& m, const char* label, bool projects) {
  testing::RecordingObserver r;
  const model::Summary s = simulate(m, r);
  ASSERT_TRUE(s.completed);
  const auto H = r.series("total_energy");
  double largest = 0, worst = 0;
  for (double h : H) largest = std::max(largest, std::abs(h));
  for (double h : H) worst = std::max(worst, std::abs(h - H.front()));
  const auto active = r.series("active_contacts"), unprojected = r.series("unprojected_nodes");
  const double most_active = *std::max_element(active.begin(), active.end());
  EXPECT_GE(most_active, 3) << "the ball meets the edge";
  if (projects) EXPECT_EQ(*std::max_element(unprojected.begin(), unprojected.end()), 0);
  EXPECT_LT(worst, 1e-10 * largest) << "max_n |H_n − H_0| / max |H|";
  EXPECT_LT(s.linear_momentum_drift, 1e-10);
  EXPECT_EQ(s.verdict, "ok");
  std::printf(
      "ball on box edge, %s: max |H_n − H_0| = %.2e max|H|, active ≤ %.0f, %.1f Newton its/step, verdict "
      "%s\n",
      label, worst / largest, most_active, s.newton_iterations_per_step, s.verdict.c_str());
}

TEST(BallOnBoxEdge, EnergyMomentumKeepsEnergyAcrossTheEdgeWithEveryNodeProjected) {
  expect_energy_across_the_edge(scene::load_file(example), "node-to-segment", true);
}

// The same with mortar contact (docs/theory.md §4.7). Slave nodes near the edge face the box's top and side
// at 30–60°, where the pairs fade (4.76): before the support of (4.84) was faded alike, those nodes never
// counted as covered and penetrated 5.6e-2 (over the verdict's bound); and a node activated while not covered
// at x_n closed its gap, 3.3 max |H| gained. Measured now: 3.4e-13, 7.2 Newton its/step.
TEST(BallOnBoxEdge, MortarKeepsEnergyAcrossTheEdge) {
  nlohmann::json written = nlohmann::json::parse(std::ifstream(example));
  for (nlohmann::json& pair : written["contact"]) pair["discretization"] = "mortar";
  expect_energy_across_the_edge(scene::load(written), "mortar", false);  // mortar projects no nodes
}

// The comparator the merge replaces: the same scene with the two pairs kept apart (built by hand, as loading
// no longer makes it). Each surface ends in a rim at the edge, so slave nodes beyond one rim see no face.
TEST(BallOnBoxEdge, KeptApartTheTwoPairsLeaveASeamAtTheEdge) {
  nlohmann::json written = nlohmann::json::parse(std::ifstream(example));
  written["contact"].erase(1);
  model::Model m = scene::load(written);
  model::ContactPair xmax = m.contact.at(0);
  xmax.master = "box/xmax";
  m.contact.push_back(xmax);
  testing::RecordingObserver r;
  r.allow_suspect();  // the seam this comparator shows puts energy in as reported jumps: (V4) fails
  const model::Summary s = simulate(m, r);
  const auto unprojected = r.series("unprojected_nodes");
  const double most_unprojected = *std::max_element(unprojected.begin(), unprojected.end());
  EXPECT_GT(most_unprojected, 0) << "the seam this merge removes";
  EXPECT_GT(s.energy_drift, 1e-2) << "and its energy error";
  std::printf(
      "ball on box edge, two pairs kept apart: %s, energy drift %.2e, unprojected ≤ %.0f, max penetration "
      "%.2e\n",
      s.completed ? "completed" : "failed", s.energy_drift, most_unprojected, s.max_penetration);
}

}  // namespace
}  // namespace stoss
