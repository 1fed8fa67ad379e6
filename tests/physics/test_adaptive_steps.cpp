// Steps chosen by a tolerance (issue 22 §2, docs/theory.md §2.7) and frames at an interval (§3):
// - energy–momentum keeps energy and both momenta to 1e-10 while its step changes: the balance (2.8)
//   holds step by step for each h;
// - series/time holds the actual step times, series/step_size their differences, row 0 of step_size and
//   rejected_steps is 0, and every rejection is logged with its reason;
// - with output.interval, frames/time[k] = k·interval exactly, with fixed and with adaptive steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "../core/recording_observer.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"

namespace stoss {
namespace {

/// A free 3 × 1 × 1 bar tumbling and vibrating (spin about a skew axis, a stretch-inducing velocity):
/// no contact, no supports, 1 s.
nlohmann::json tumbling_bar(const nlohmann::json& time, const nlohmann::json& output = {{"every", 1}}) {
  return {{"format", "stoss-scene/1"},
          {"name", "tumbling bar, adaptive steps"},
          {"bodies",
           {{{"name", "bar"},
             {"mesh",
              {{"box", {{"min", {-1.5, -0.5, -0.5}}, {"max", {1.5, 0.5, 0.5}}, {"divisions", {3, 1, 1}}}}}},
             {"material",
              {{"model", "saint_venant_kirchhoff"},
               {"youngs_modulus", 200},
               {"poisson_ratio", 0.3},
               {"density", 1}}},
             {"initial_velocity", {0.3, 0, 0}},
             {"initial_angular_velocity", {0.5, 1.5, 4}}}}},
          {"time", time},
          {"solver", {{"tolerance", 1e-12}}},
          {"output", output}};
}

double largest(const std::vector<double>& v) {
  return *std::max_element(v.begin() + 1, v.end());
}
double smallest(const std::vector<double>& v) {
  return *std::min_element(v.begin() + 1, v.end());
}

TEST(AdaptiveSteps, EnergyMomentumKeepsEnergyAndMomentaWhileTheStepChanges) {
  const model::Model m = scene::load(tumbling_bar({{"step", 0.02}, {"end", 1.0}, {"tolerance", 1e-4}}));
  testing::RecordingObserver r;
  const model::Summary s = simulate(m, r);
  ASSERT_TRUE(s.completed);
  const std::vector<double> h = r.series("step_size");
  ASSERT_GT(largest(h), 1.5 * smallest(h)) << "the step did not change: no test";
  EXPECT_EQ(h[0], 0);
  EXPECT_EQ(r.series("rejected_steps")[0], 0);
  EXPECT_LT(s.energy_drift, 1e-10);
  EXPECT_LT(s.linear_momentum_drift, 1e-10);
  EXPECT_LT(s.angular_momentum_drift, 1e-10);
  // series/time holds the step times: each row's time is the last one's plus its step.
  for (size_t n = 1; n < r.rows.size(); ++n)
    EXPECT_NEAR(r.rows[n].time, r.rows[n - 1].time + h[n], 1e-15) << "row " << n;
  EXPECT_EQ(r.rows.back().time, 1.0);
  // Every rejection is logged with its reason.
  const auto rejections = std::count_if(r.logs.begin(), r.logs.end(), [](const std::string& line) {
    return line.rfind("rejected step at t = ", 0) == 0 && line.find(", h = ") != std::string::npos &&
           (line.find(": error: estimate ") != std::string::npos ||
            line.find(": newton: ") != std::string::npos);
  });
  const std::vector<double> rejected = r.series("rejected_steps");
  EXPECT_EQ(rejections, std::accumulate(rejected.begin(), rejected.end(), 0.0));
  std::printf("tumbling bar, TOL 1e-4: %d steps, h %.2e…%.2e, %ld rejected, energy %.1e\n", s.steps,
              smallest(h), largest(h), long(rejections), s.energy_drift);
}

TEST(AdaptiveSteps, AToleranceTenTimesSmallerTakesMoreSteps) {
  const auto steps = [](double tolerance) {
    testing::RecordingObserver r;
    return simulate(scene::load(tumbling_bar({{"step", 0.02}, {"end", 0.5}, {"tolerance", tolerance}})), r)
        .steps;
  };
  EXPECT_GT(steps(1e-5), 1.5 * steps(1e-4)) << "ê ∝ h³ (2.16): 10× the tolerance, about 2.2× the steps";
}

// frames/time[k] = k·interval exactly, whatever the steps: fixed steps that do not divide the interval,
// and steps chosen by a tolerance.
TEST(AdaptiveSteps, FramesAtAnIntervalLandOnItsMultiplesExactly) {
  for (const nlohmann::json& time : {nlohmann::json{{"step", 0.03}, {"end", 0.6}},
                                     nlohmann::json{{"step", 0.02}, {"end", 0.6}, {"tolerance", 1e-4}}}) {
    SCOPED_TRACE(time.dump());
    testing::RecordingObserver r;
    ASSERT_TRUE(simulate(scene::load(tumbling_bar(time, {{"interval", 0.1}})), r).completed);
    ASSERT_EQ(r.frames.size(), 7u);
    for (size_t k = 0; k < r.frames.size(); ++k) EXPECT_EQ(r.frames[k].time, static_cast<double>(k) * 0.1);
    EXPECT_EQ(r.rows.back().time, 6 * 0.1);
  }
}

}  // namespace
}  // namespace stoss
