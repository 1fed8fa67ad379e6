// Automatic step reduction (time/step_reduction.hpp, issue 6 item 4). The system shall solve a step
// whose Newton solve fails in substeps, record their number in the `substeps` series and log it, keep
// energy_momentum's conservation through the substeps, and fail a hopeless run with an error that
// names the step and the time, never with a NaN in the results.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/mesh/generators.hpp"
#include "core/simulate.hpp"
#include "tests/core/recording_observer.hpp"

namespace stoss {
namespace {

using testing::RecordingObserver;

/// A stiff 2×1×1 bar (E = 1e4, ν = 0.3, ρ = 1) spinning fast, ω = (3, 6, 12): at h = 0.05 a step turns it
/// by ~40°, far from the predictor, so a tight Newton budget fails there and not in half steps.
model::Model fast_stiff_bar(double h, int steps, int max_iterations) {
  model::Model m;
  m.mesh.add_body("bar", mesh::box({0, 0, 0}, {2, 1, 1}, {4, 2, 2}));
  model::BodySpec b;
  b.name = "bar";
  b.material = {"saint_venant_kirchhoff", 1e4, 0.3, 1};
  b.initial_velocity = {0.3, -0.2, 0.1};
  b.initial_angular_velocity = {3, 6, 12};
  m.bodies.push_back(b);
  m.time = {model::Scheme::energy_momentum, h, h * steps};
  m.solver.tolerance = 1e-11;
  m.solver.max_iterations = max_iterations;
  m.output.every = 10;
  m.effects = model::resolve_effects(m);
  return m;
}

TEST(StepReduction, AFailingStepIsSolvedInSubstepsAndRecorded) {
  const int budget = 6;  // measured: 8 converges every full step, 6 needs 2–3 substeps, 3 is hopeless
  RecordingObserver r;
  const model::Summary s = simulate(fast_stiff_bar(0.05, 20, budget), r);
  ASSERT_TRUE(s.completed);
  ASSERT_TRUE(r.has_series("substeps"));
  const auto substeps = r.series("substeps");
  EXPECT_EQ(substeps.front(), 1) << "the initial row";
  const double most = *std::max_element(substeps.begin(), substeps.end());
  EXPECT_GT(most, 1) << "a " << budget << "-iteration budget must fail at the full step";
  EXPECT_LE(most, 16) << "at most 4 halvings";
  const bool logged = std::any_of(r.logs.begin(), r.logs.end(), [](const std::string& line) {
    return line.find("automatic step reduction") != std::string::npos;
  });
  EXPECT_TRUE(logged);
  // Energy–momentum conserves H in every substep (2.8), so through the whole reduced run.
  const auto H = r.series("total_energy");
  EXPECT_LT(testing::max_drift(H, H.front()), 1e-9);
  EXPECT_LT(r.vector_drift("angular_momentum"), 1e-10);
  EXPECT_EQ(r.rows.size(), 21u) << "one row per step, whatever its substeps";
  EXPECT_NEAR(r.rows.back().time, 1.0, 1e-12);
  EXPECT_TRUE(r.all_finite());
  std::printf("budget %d: max substeps %.0f, %d steps reduced\n", budget, most,
              int(std::count_if(substeps.begin(), substeps.end(), [](double k) { return k > 1; })));
}

TEST(StepReduction, AHopelessRunFailsNamingStepAndTimeWithoutNaN) {
  RecordingObserver r;
  try {
    simulate(fast_stiff_bar(0.05, 20, 1), r);  // one iteration never converges a nonlinear step
    FAIL() << "expected a SolverError";
  } catch (const SolverError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("step 1 (t = 0 → 0.05) did not converge"), std::string::npos) << what;
    EXPECT_NE(what.find("with automatic step reduction it still failed at t = "), std::string::npos) << what;
    EXPECT_NE(what.find("h/16"), std::string::npos) << what;
    EXPECT_NE(what.find("residual history"), std::string::npos) << what;
  }
  EXPECT_FALSE(r.summary.completed);
  EXPECT_TRUE(r.all_finite());
}

}  // namespace
}  // namespace stoss
