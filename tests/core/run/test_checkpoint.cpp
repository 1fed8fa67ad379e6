// Checkpoints and resume (issue 10 item 4): the system shall write the full state of a run every
// output.checkpoint_every steps, and a run resumed from the last checkpoint after a crash shall compute only
// the steps after it and end with the series and frames of a run that never crashed, to the Newton tolerance.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <set>
#include <stdexcept>
#include <string>

#include "../recording_observer.hpp"
#include "../short_ball_on_plate.hpp"
#include "core/run/checkpoint.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"

namespace stoss {
namespace {

namespace fs = std::filesystem;
using testing::RecordingObserver;

/// A fresh directory under the system's temporary directory, removed at the end of the test.
struct TempDir {
  fs::path path = fs::temp_directory_path() /
                  ("stoss_checkpoint_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  TempDir() { fs::remove_all(path); }
  ~TempDir() { fs::remove_all(path); }
  static inline int counter = 0;
};

/// The shortened seed's example (short_ball_on_plate.hpp), 24 steps: "lagrange" (frictionless: mixed
/// energy–momentum, or with "hht" the α-weighted form that keeps λ_n N_s(x_n) between steps) or "penalty"
/// with Coulomb friction μ = 0.2.
nlohmann::json ball_on_plate(const std::string& enforcement, int checkpoint_every,
                             const std::string& scheme = "energy_momentum") {
  return test::short_ball_on_plate({enforcement, scheme, false, 0.24, checkpoint_every});
}

struct Crash : std::runtime_error {
  Crash() : std::runtime_error("crash") {}
};

/// Records the run and dies (throws Crash) when the row of step `crash_at` arrives, before the run can write
/// a checkpoint at that step: what kill -9 does to a process at that moment.
class CrashingObserver : public RecordingObserver {
 public:
  explicit CrashingObserver(int crash_at = -1) : crash_at_(crash_at) {}
  void step(const model::StepRow& r) override {
    if (r.step == crash_at_) throw Crash();
    RecordingObserver::step(r);
    events.push_back("step " + std::to_string(r.step));
  }
  void log(const std::string& line) override {
    RecordingObserver::log(line);
    if (line.rfind("resumed from step", 0) == 0) events.push_back(line);
  }
  void resumed(int step) override { resumed_at.push_back(step); }
  std::vector<std::string> events;  ///< rows and the resume line, in the order they came
  std::vector<int> resumed_at;      ///< the steps Observer::resumed named

 private:
  int crash_at_;
};

/// Every physical series (not the wall time nor the solver's own: step_seconds, residual_norm,
/// newton_iterations, substeps) equal in both runs to `tolerance` relative to the series' scale (its largest
/// value over steps and components, at least 1e-6: the scenes' energies, momenta and lengths are of order 1),
/// every frame's positions and velocities too.
void expect_same_run(const RecordingObserver& a, const RecordingObserver& b, double tolerance) {
  ASSERT_EQ(a.rows.size(), b.rows.size());
  ASSERT_EQ(a.frames.size(), b.frames.size());
  const std::set<std::string> not_physical{"step_seconds", "residual_norm", "newton_iterations", "substeps"};
  int column = 0;
  for (const model::SeriesSpec& spec : a.layout.series) {
    const int first = column;
    column += spec.components;
    if (not_physical.contains(spec.name)) continue;
    double scale = 1e-6;
    for (const auto& row : a.rows)
      for (int k = first; k < column; ++k) scale = std::max(scale, std::abs(row.values[k]));
    for (size_t n = 0; n < a.rows.size(); ++n) {
      EXPECT_EQ(a.rows[n].step, b.rows[n].step);
      for (int k = first; k < column; ++k)
        EXPECT_NEAR(a.rows[n].values[k], b.rows[n].values[k], tolerance * scale)
            << spec.name << "[" << k - first << "] at step " << a.rows[n].step;
    }
  }
  for (size_t k = 0; k < a.frames.size(); ++k) {
    EXPECT_EQ(a.frames[k].time, b.frames[k].time);
    EXPECT_LE((a.frames[k].position - b.frames[k].position).norm(), tolerance * a.frames[k].position.norm());
    EXPECT_LE((a.frames[k].velocity - b.frames[k].velocity).norm(),
              tolerance * std::max(a.frames[k].velocity.norm(), 1.0));
  }
}

class CheckpointResume : public ::testing::TestWithParam<std::pair<std::string, std::string>> {};

TEST_P(CheckpointResume, AResumedRunComputesOnlyTheStepsAfterTheCheckpointAndEndsAsAnUncrashedRun) {
  const model::Model m = scene::load(ball_on_plate(GetParam().first, 4, GetParam().second));
  TempDir uncrashed_dir, crashed_dir;
  CrashingObserver uncrashed;
  const model::Summary reference = simulate(m, uncrashed, nullptr, {uncrashed_dir.path, false});
  ASSERT_TRUE(reference.completed);
  ASSERT_GT(reference.max_penetration + uncrashed.series("active_contacts").back(), 0)
      << "no contact: no test";

  for (int crash_at : {3, 13, 21}) {
    SCOPED_TRACE("crash at step " + std::to_string(crash_at));
    TempDir dir;
    CrashingObserver first(crash_at);
    EXPECT_THROW(simulate(m, first, nullptr, {dir.path, true}), Crash);
    const int checkpoint = (crash_at - 1) / 4 * 4;  // the last one before the crash
    EXPECT_EQ(run::CheckpointStore(dir.path).exists(), checkpoint > 0);

    CrashingObserver resumed;
    const model::Summary summary = simulate(m, resumed, nullptr, {dir.path, true});
    EXPECT_TRUE(summary.completed);
    EXPECT_EQ(summary.resumed_from_step, checkpoint);
    EXPECT_EQ(summary.steps, reference.steps);
    // HHT's λ_n N_s(x_n) is rebuilt from the checkpoint (its ξ re-projected): equal to round-off, not bit
    // for bit, so Newton may take another iteration there.
    if (GetParam().second != "hht") {
      EXPECT_EQ(summary.newton_iterations, reference.newton_iterations);
    }
    EXPECT_NEAR(summary.energy_drift, reference.energy_drift, 1e-8);
    expect_same_run(uncrashed, resumed, 1e-9);
    if (checkpoint == 0) continue;
    // Steps 0..N come back as they were (their wall times are the first attempt's), then the log line, then
    // steps N+1.. only.
    ASSERT_EQ(resumed.events.size(), size_t(reference.steps + 2));
    EXPECT_EQ(resumed.resumed_at, std::vector<int>{checkpoint})
        << "observers hear of the resume once, with its step";
    EXPECT_EQ(
        resumed.events[checkpoint + 1].rfind("resumed from step " + std::to_string(checkpoint) + " ", 0), 0u)
        << resumed.events[checkpoint + 1];
    for (int n = 0; n <= checkpoint; ++n) {
      EXPECT_EQ(resumed.events[n], "step " + std::to_string(n));
      EXPECT_EQ(resumed.series("step_seconds")[n], first.series("step_seconds")[n]);
    }
    for (int n = checkpoint + 1; n <= reference.steps; ++n)
      EXPECT_EQ(resumed.events[n + 1], "step " + std::to_string(n));
  }
}

INSTANTIATE_TEST_SUITE_P(LagrangeAndPenaltyFriction, CheckpointResume,
                         ::testing::Values(std::pair<std::string, std::string>{"lagrange", "energy_momentum"},
                                           std::pair<std::string, std::string>{"penalty", "energy_momentum"},
                                           std::pair<std::string, std::string>{"lagrange", "hht"}),
                         [](const auto& info) { return info.param.first + "_" + info.param.second; });

// With steps chosen by a tolerance (issue 22 §4) the step controller's state is part of the checkpoint: a
// run resumed from one takes the same steps (times, step_size, rejected_steps) and ends bit for bit as the
// run that never crashed.
TEST(Checkpoint, AResumedRunWithAToleranceTakesTheSameStepsBitForBit) {
  nlohmann::json scene = ball_on_plate("lagrange", 3);
  scene["time"]["tolerance"] = 1e-3;
  scene["time"]["end"] = 0.12;
  const model::Model m = scene::load(scene);
  TempDir uncrashed_dir;
  CrashingObserver uncrashed;
  const model::Summary reference = simulate(m, uncrashed, nullptr, {uncrashed_dir.path, false});
  ASSERT_TRUE(reference.completed);
  const std::vector<double> h = uncrashed.series("step_size"), rejected = uncrashed.series("rejected_steps");
  ASSERT_GT(*std::max_element(h.begin() + 1, h.end()), 1.5 * *std::min_element(h.begin() + 1, h.end()))
      << "the steps do not vary: no test";
  std::printf("ball on plate, TOL 1e-3: %d steps, h %.2e…%.2e, %.0f rejected\n", reference.steps,
              *std::min_element(h.begin() + 1, h.end()), *std::max_element(h.begin() + 1, h.end()),
              std::accumulate(rejected.begin(), rejected.end(), 0.0));
  ASSERT_GT(std::accumulate(rejected.begin(), rejected.end(), 0.0), 0) << "no step rejected: no test";
  for (int crash_at : {reference.steps / 3, 2 * reference.steps / 3 + 1}) {
    SCOPED_TRACE("crash at step " + std::to_string(crash_at));
    TempDir dir;
    CrashingObserver first(crash_at);
    EXPECT_THROW(simulate(m, first, nullptr, {dir.path, true}), Crash);
    ASSERT_TRUE(run::CheckpointStore(dir.path).exists());
    ASSERT_TRUE(run::CheckpointStore(dir.path).read().controller.has_value());
    CrashingObserver resumed;
    const model::Summary summary = simulate(m, resumed, nullptr, {dir.path, true});
    EXPECT_TRUE(summary.completed);
    EXPECT_GT(summary.resumed_from_step, 0);
    EXPECT_EQ(summary.steps, reference.steps);
    EXPECT_EQ(summary.newton_iterations, reference.newton_iterations);
    expect_same_run(uncrashed, resumed, 0.0);  // step_size and rejected_steps included
  }
}

TEST(Checkpoint, ACheckpointOfAnotherSceneIsRefusedWithTheReason) {
  TempDir dir;
  CrashingObserver first(9);
  EXPECT_THROW(simulate(scene::load(ball_on_plate("lagrange", 4)), first, nullptr, {dir.path, true}), Crash);
  nlohmann::json other = ball_on_plate("lagrange", 4);
  other["bodies"][0]["initial_velocity"] = {0, 1, -2};
  CrashingObserver second;
  try {
    simulate(scene::load(other), second, nullptr, {dir.path, true});
    FAIL() << "resumed another scene's checkpoint";
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("it was written for another scene"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("state.h5"), std::string::npos) << e.what();
  }
}

TEST(Checkpoint, TheStateFileHoldsTheFullStateOfItsStep) {
  TempDir dir;
  const model::Model m = scene::load(ball_on_plate("penalty", 5));
  CrashingObserver run(12);
  EXPECT_THROW(simulate(m, run, nullptr, {dir.path, false}), Crash);
  const run::Checkpoint c = run::CheckpointStore(dir.path).read();
  EXPECT_EQ(c.state.step, 10);
  EXPECT_NEAR(c.state.t, 0.1, 1e-12);
  EXPECT_EQ(c.state.x.size(), m.dof_count());
  EXPECT_EQ(c.rows.size(), 11u);  // steps 0..10
  EXPECT_EQ(c.frame_steps, (std::vector<int>{0, 3, 6, 9}));
  ASSERT_EQ(c.terms.size(), 2u);  // elasticity, the pair
  EXPECT_EQ(c.terms[1].second.integers.at("face").size(), c.terms[1].second.reals.at("gap_offset").size());
  EXPECT_EQ(c.terms[1].second.reals.at("friction_traction").size(),
            3 * c.terms[1].second.reals.at("gap_offset").size());
  EXPECT_GE(c.terms[1].second.reals.at("dissipated_energy").at(0), 0.0);
  // Positions of step 10 as the run reported them.
  EXPECT_EQ(c.rows.back().values, run.rows[10].values);
}

TEST(Checkpoint, TheScheduleFieldsAreValidatedWithTheirPointers) {
  nlohmann::json scene = ball_on_plate("lagrange", 0);
  scene["output"]["checkpoint_seconds"] = -1;
  try {
    scene::load(scene);
    FAIL() << "accepted checkpoint_every 0 and checkpoint_seconds -1";
  } catch (const scene::SceneError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("/output/checkpoint_every"), std::string::npos) << what;
    EXPECT_NE(what.find("/output/checkpoint_seconds"), std::string::npos) << what;
  }
  const model::Model m = scene::load(ball_on_plate("lagrange", 7));
  EXPECT_EQ(m.output.checkpoint_every, 7);
  nlohmann::json defaults = ball_on_plate("lagrange", 1);
  defaults["output"].erase("checkpoint_every");
  EXPECT_EQ(scene::load(defaults).output.checkpoint_seconds, 60);
  EXPECT_EQ(scene::load(defaults).output.checkpoint_every, 0);
}

}  // namespace
}  // namespace stoss
