// Progress reports: the system shall report a run's progress about twice a second, not every step,
// with an ETA, and once more at the end.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/scene/estimates.hpp"
#include "core/scene/scene.hpp"
#include "server/jobs/reporting/job_observer.hpp"

namespace stoss::server::jobs {
namespace {

model::Model model_of(int steps) {
  model::Model m;
  m.time.step = 0.01;
  m.time.end = 0.01 * steps;
  return m;
}

TEST(ProgressObserver, ReportsAtMostOncePerIntervalWithAnEta) {
  ManualClock clock;
  std::vector<Progress> reports;
  ProgressObserver observer([&](const Progress& p) { reports.push_back(p); }, clock, 500);
  observer.begin(model_of(1000), {});
  ASSERT_EQ(reports.size(), 1u);  // step 0 right away
  EXPECT_EQ(reports[0].steps, 1000);
  for (int step = 1; step <= 100; ++step) {
    clock.advance(10);  // 100 steps per second
    observer.step({step, 0.01 * step, {}});
  }
  // One second of steps: reports at 500 ms and 1000 ms, not 100.
  ASSERT_EQ(reports.size(), 3u);
  EXPECT_EQ(reports[1].step, 50);
  EXPECT_EQ(reports[2].step, 100);
  EXPECT_NEAR(reports[2].time, 1.0, 1e-12);
  ASSERT_TRUE(reports[2].eta_seconds);
  EXPECT_NEAR(*reports[2].eta_seconds, 9.0, 1e-9);  // 900 steps to go at 10 ms each
  observer.end({});
  EXPECT_EQ(reports.size(), 4u);
}

TEST(ProgressObserver, TheFirstEtaIsTheEstimateMadeBeforeTheRun) {
  const model::Model seed =
      scene::load_file(std::string(STOSS_SOURCE_DIR) + "/api/examples/hollow_ball_plate.json");
  ManualClock clock;
  std::vector<Progress> reports;
  ProgressObserver observer([&](const Progress& p) { reports.push_back(p); }, clock, 500);
  observer.begin(seed, {});
  ASSERT_EQ(reports.size(), 1u);
  ASSERT_TRUE(reports[0].eta_seconds);
  EXPECT_GT(*reports[0].eta_seconds, 0);
  EXPECT_DOUBLE_EQ(*reports[0].eta_seconds, scene::estimate(seed).wall_seconds);  // (W7)
  clock.advance(20);
  observer.step({1, 0.01, {}});  // then the run's own rate: 99 steps to go at 20 ms each
  observer.end({});
  EXPECT_NEAR(*reports.back().eta_seconds, 99 * 0.02, 1e-9);
}

TEST(ProgressObserver, TheFinalReportOfACompletedRunHasEtaZero) {
  ManualClock clock;
  Progress last;
  ProgressObserver observer([&](const Progress& p) { last = p; }, clock, 500);
  observer.begin(model_of(3), {});
  for (int step = 1; step <= 3; ++step) observer.step({step, 0.01 * step, {}});
  observer.end({});
  EXPECT_EQ(last.step, 3);
  EXPECT_EQ(last.eta_seconds, 0.0);
}

TEST(ProgressObserver, AResumedRunsEtaCountsFromTheCheckpointNotFromTheRowsGivenBack) {
  ManualClock clock;
  std::vector<Progress> reports;
  ProgressObserver observer([&](const Progress& p) { reports.push_back(p); }, clock, 500);
  observer.begin(model_of(1000), {});
  for (int step = 0; step <= 600; ++step) observer.step({step, 0.01 * step, {}});  // given back at once
  observer.resumed(600);
  for (int step = 601; step <= 700; ++step) {
    clock.advance(10);  // 100 steps per second
    observer.step({step, 0.01 * step, {}});
  }
  observer.end({});
  ASSERT_TRUE(reports.back().eta_seconds);
  EXPECT_EQ(reports.back().step, 700);
  EXPECT_NEAR(*reports.back().eta_seconds, 3.0, 1e-9);  // 300 steps to go at 10 ms each
}

// With time.tolerance the steps to go are unknown (issue 22 §2): the fraction done is time/end, the ETA
// comes from the wall time per unit of simulated time, and `steps` is the count at the mean step so far.
TEST(ProgressObserver, WithAToleranceProgressAndEtaGoBySimulatedTime) {
  ManualClock clock;
  std::vector<Progress> reports;
  ProgressObserver observer([&](const Progress& p) { reports.push_back(p); }, clock, 500);
  model::Model m = model_of(100);  // end 1, first step 0.01
  m.time.tolerance = 1e-3;
  observer.begin(m, {});
  EXPECT_EQ(reports[0].steps, 100) << "before a step: end / time.step";
  double t = 0;
  for (int step = 1; step <= 50; ++step) {  // 50 steps of 0.005 over 2 s, then 10 of 0.025 over 1 s
    clock.advance(40);
    observer.step({step, t += 0.005, {}});
  }
  for (int step = 51; step <= 60; ++step) {
    clock.advance(100);
    observer.step({step, t += 0.025, {}});
  }
  const Progress& p = observer.current();
  EXPECT_NEAR(p.time, 0.5, 1e-12);
  EXPECT_EQ(p.steps, 120) << "60 steps to t = 0.5 of 1: step/steps = time/end";
  ASSERT_TRUE(p.eta_seconds);
  EXPECT_NEAR(*p.eta_seconds, 3.0, 1e-9)
      << "3 s for half the time, 3 s for the other half (steps of end/time.step would say 2 s)";
  for (int step = 61; step <= 80; ++step) {
    clock.advance(100);
    observer.step({step, t += 0.025, {}});
  }
  observer.end({});
  EXPECT_EQ(reports.back().steps, 80);
  EXPECT_EQ(reports.back().eta_seconds, 0.0);
}

TEST(ProgressObserver, WithAToleranceAResumedRunsEtaCountsTheTimeSinceTheCheckpoint) {
  ManualClock clock;
  ProgressObserver observer({}, clock, 500);
  model::Model m = model_of(100);
  m.time.tolerance = 1e-3;
  observer.begin(m, {});
  for (int step = 0; step <= 10; ++step) observer.step({step, 0.06 * step, {}});  // given back at once
  observer.resumed(10);
  clock.advance(1000);
  observer.step({11, 0.7, {}});  // 0.1 of simulated time in 1 s, 0.3 to go
  ASSERT_TRUE(observer.current().eta_seconds);
  EXPECT_NEAR(*observer.current().eta_seconds, 3.0, 1e-9);
  EXPECT_EQ(observer.current().steps, 16);  // 11 · 1/0.7 = 15.7
}

TEST(SummaryJson, NamesTheCheckpointStepOfAResumedRun) {
  model::Summary s;
  s.completed = true;
  s.steps = 10;
  EXPECT_FALSE(summary_json(s, model_of(10)).contains("resumed_from_step"));
  s.resumed_from_step = 6;
  EXPECT_EQ(summary_json(s, model_of(10))["resumed_from_step"], 6);
}

// The wall time's parts, the linear solver's split into factorisations and solves among them (docs/api.md).
TEST(SummaryJson, SplitsTheLinearSolverTimeIntoFactorisationsAndSolves) {
  model::Summary s;
  s.linear_factorization_seconds = 1.25;
  s.linear_solve_seconds = 0.5;
  s.linear_solver_seconds = 1.75;
  const nlohmann::json j = summary_json(s, model_of(10));
  EXPECT_EQ(j["linear_factorization_seconds"], 1.25);
  EXPECT_EQ(j["linear_solve_seconds"], 0.5);
  EXPECT_EQ(j["linear_solver_seconds"], 1.75);
}

// Krylov iterations per solve and LU fallbacks appear when a Krylov method ran (docs/api.md).
TEST(SummaryJson, CarriesKrylovCountsOnlyWhenAKrylovMethodRan) {
  model::Summary s;
  const model::Model m = model_of(10);
  EXPECT_FALSE(summary_json(s, m).contains("krylov_iterations_per_solve"));
  s.krylov_iterations_per_solve = 23.4;
  s.krylov_fallbacks = 1;
  const nlohmann::json j = summary_json(s, m);
  EXPECT_EQ(j["krylov_iterations_per_solve"], 23.4);
  EXPECT_EQ(j["krylov_fallbacks"], 1);
}

TEST(SummaryJson, CarriesMaxPenetrationOnlyWithContact) {
  model::Summary s;
  s.completed = true;
  s.energy_drift = 1e-12;
  s.max_penetration = 0.25;
  s.newton_iterations = 42;
  s.wall_seconds = 1.5;
  model::Model m = model_of(10);
  nlohmann::json j = summary_json(s, m);
  EXPECT_EQ(j["energy_drift"], 1e-12);
  EXPECT_EQ(j["newton_iterations"], 42);
  EXPECT_EQ(j["wall_seconds"], 1.5);
  // docs/api.md: energy drift, momentum drift, iterations per step and wall seconds in every summary.
  for (const char* key : {"energy_drift", "linear_momentum_drift", "angular_momentum_drift", "wall_seconds",
                          "newton_iterations_per_step"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_FALSE(j.contains("max_penetration"));
  m.contact.push_back({});
  EXPECT_EQ(summary_json(s, m)["max_penetration"], 0.25);
}

// issue 23 §4: the summary names external_work (series/external_work at its end) where the scene has loads
// or prescribed motion, and only there.
TEST(SummaryJson, NamesTheExternalWorkOnlyWithLoadsOrPrescribedMotion) {
  model::Summary s;
  s.external_work = 0.75;
  model::Model m = model_of(10);
  EXPECT_FALSE(summary_json(s, m).contains("external_work"));
  m.loads.push_back({});
  EXPECT_EQ(summary_json(s, m)["external_work"], 0.75);
  m.loads.clear();
  m.effects.push_back(model::effect::prescribed_motion);
  EXPECT_EQ(summary_json(s, m)["external_work"], 0.75);
}

// The log's last line of a run that counts external work gives the drift of H − W_ext and the work; static
// load steps keep no energy between load levels, and their line says the drift is not reported.
TEST(LogObserver, TheEnergyLineOfARunWithExternalWorkIsHMinusW) {
  const auto end_line = [](bool external_work, model::Scheme scheme = model::Scheme::energy_momentum) {
    const std::filesystem::path path = std::filesystem::temp_directory_path() / "stoss_log_observer_work.log";
    {
      std::ofstream out(path);
      LogObserver log(out);
      model::SeriesLayout layout;
      layout.series.push_back({"total_energy", 1, false, 0});
      if (external_work) layout.series.push_back({"external_work", 1, false, 0});
      model::Model m;
      m.time.scheme = scheme;
      log.begin(m, layout);
      model::Summary s;
      s.completed = true;
      s.energy_drift = 2e-13;
      s.external_work = 0.5;
      log.end(s);
    }
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    std::filesystem::remove(path);
    return line;
  };
  const std::string loaded = end_line(true), free = end_line(false);
  EXPECT_NE(loaded.find("energy drift (H − W_ext) 2e-13, external work 0.5,"), std::string::npos) << loaded;
  EXPECT_NE(free.find("energy drift 2e-13,"), std::string::npos) << free;
  EXPECT_EQ(free.find("external work"), std::string::npos) << free;
  const std::string static_steps = end_line(true, model::Scheme::equilibrium);
  EXPECT_NE(static_steps.find("energy drift not reported (static load steps), external work 0.5,"),
            std::string::npos)
      << static_steps;
}

// Solver lines in a job's log name the step they belong to and the time it starts from; other lines
// are written as they come.
TEST(LogObserver, NewtonLinesNameTheirStepAndItsStartTime) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "stoss_log_observer_test.log";
  {
    std::ofstream out(path);
    LogObserver log(out);
    log.log("linear solver: direct");
    model::StepRow row;
    row.step = 4;
    row.time = 0.05;
    log.step(row);
    log.log("newton: residual 3.9e+00 after a full step, halving it (scale 0.5)");
    log.log("contact ball/outer on plate/top: penalty");
  }
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::filesystem::remove(path);
  EXPECT_EQ(text.str(),
            "linear solver: direct\n"
            "step 5 (from t = 0.05): newton: residual 3.9e+00 after a full step, halving it (scale 0.5)\n"
            "contact ball/outer on plate/top: penalty\n");
}

}  // namespace
}  // namespace stoss::server::jobs
