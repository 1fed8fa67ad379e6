// The system shall give bit-identical results for a run made alone and the same run made while another
// simulate() runs on another thread of the same process (issue 10, "What must hold" 5): no state shared
// between runs (orderings, solver settings, caches) may leak from one into the other. Threads, not
// processes, because separate processes would hide such state. Every series except the wall-time one,
// every frame (positions, velocities, contact pressure), the log and the summary's counts are compared
// bit for bit.
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "../core/recording_observer.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"

namespace stoss {
namespace {

using testing::RecordingObserver;

/// An example scene cut to `end` (the impact is at t ≈ 0.3 in both examples used here).
model::Model example(const std::string& file, double end) {
  model::Model m = scene::load_file(std::string(STOSS_SOURCE_DIR) + "/api/examples/" + file);
  m.time.end = end;
  return m;
}

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

/// Index of the first entry whose bits differ, -1 when every bit agrees (sizes included).
long first_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  if (a.size() != b.size()) return 0;
  for (Eigen::Index i = 0; i < a.size(); ++i)
    if (!same_bits(a[i], b[i])) return long(i);
  return -1;
}

/// Every series but step_seconds (wall time), every frame and the log of the second run `b` equal the
/// first run `a`'s bit for bit.
void expect_bit_identical(const RecordingObserver& a, const RecordingObserver& b, const std::string& what) {
  ASSERT_TRUE(a.summary.completed) << what;
  ASSERT_TRUE(b.summary.completed) << what;
  ASSERT_EQ(a.rows.size(), b.rows.size()) << what;
  const int wall = a.layout.index_of("step_seconds");
  ASSERT_GE(wall, 0) << what;
  for (size_t n = 0; n < a.rows.size(); ++n) {
    ASSERT_EQ(a.rows[n].values.size(), b.rows[n].values.size()) << what << ", step " << n;
    for (const auto& spec : a.layout.series) {
      const int at = a.layout.index_of(spec.name);
      if (at == wall) continue;
      for (int k = 0; k < spec.components; ++k)
        ASSERT_TRUE(same_bits(a.rows[n].values[at + k], b.rows[n].values[at + k]))
            << what << ": series " << spec.name << "[" << k << "] differs at step " << n << ": "
            << a.rows[n].values[at + k] << " in the first, " << b.rows[n].values[at + k] << " in the second";
    }
  }
  ASSERT_EQ(a.frames.size(), b.frames.size()) << what;
  for (size_t f = 0; f < a.frames.size(); ++f) {
    EXPECT_EQ(first_difference(a.frames[f].position, b.frames[f].position), -1) << what << ", frame " << f;
    EXPECT_EQ(first_difference(a.frames[f].velocity, b.frames[f].velocity), -1) << what << ", frame " << f;
    EXPECT_EQ(first_difference(a.frames[f].contact_pressure, b.frames[f].contact_pressure), -1)
        << what << ", frame " << f;
  }
  EXPECT_EQ(a.logs, b.logs) << what;
  EXPECT_EQ(a.summary.newton_iterations, b.summary.newton_iterations) << what;
  EXPECT_TRUE(same_bits(a.summary.energy_drift, b.summary.energy_drift)) << what;
}

TEST(ConcurrentRuns, TwoContactRunsOnThreadsEqualTheSameRunsMadeAloneBitForBit) {
  // Frictionless Lagrange contact (mixed energy–momentum, smooth master) and penalty Coulomb friction:
  // the two contact paths, into the impact (steps 31–36).
  const model::Model lagrange = example("hollow_ball_plate.json", 0.36);
  const model::Model friction = example("hollow_ball_plate_friction.json", 0.36);
  RecordingObserver lagrange_alone, friction_alone;
  simulate(lagrange, lagrange_alone);
  simulate(friction, friction_alone);
  ASSERT_GT(lagrange_alone.contact_window().first, 0) << "the run must reach the impact";
  ASSERT_GT(friction_alone.contact_window().first, 0) << "the run must reach the impact";

  // Each pair runs side by side: the two different scenes, then two copies of the same one.
  RecordingObserver lagrange_beside, friction_beside, lagrange_twin_1, lagrange_twin_2;
  {
    std::jthread a([&] { simulate(lagrange, lagrange_beside); });
    std::jthread b([&] { simulate(friction, friction_beside); });
  }
  {
    std::jthread a([&] { simulate(lagrange, lagrange_twin_1); });
    std::jthread b([&] { simulate(lagrange, lagrange_twin_2); });
  }
  expect_bit_identical(lagrange_alone, lagrange_beside, "frictionless run beside the frictional one");
  expect_bit_identical(friction_alone, friction_beside, "frictional run beside the frictionless one");
  expect_bit_identical(lagrange_alone, lagrange_twin_1, "frictionless run beside its twin (first)");
  expect_bit_identical(lagrange_alone, lagrange_twin_2, "frictionless run beside its twin (second)");
}

/// A fresh directory for one run's checkpoints, removed with its contents.
struct CheckpointDir {
  explicit CheckpointDir(const std::string& name)
      : path(std::filesystem::temp_directory_path() /
             ("stoss_concurrent_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~CheckpointDir() { std::filesystem::remove_all(path); }
  std::filesystem::path path;
};

TEST(ConcurrentRuns, WhereCheckpointsByWallTimeLandDoesNotChangeTheResult) {
  // A job keeps checkpoints every output.checkpoint_seconds of wall time (default 60), so on which steps
  // they land depends on how fast the run goes: slower beside another job. A checkpoint makes the next
  // step refactorise (a run resumed from it must compute what the run that went on computes), so it
  // must not matter where they land. The two extremes: a checkpoint at every step it may go, and none.
  model::Model often = example("hollow_ball_plate_friction.json", 0.36), never = often;
  often.output.checkpoint_every = never.output.checkpoint_every = 0;
  often.output.checkpoint_seconds = 0;
  never.output.checkpoint_seconds = 1e9;
  CheckpointDir often_dir("often"), never_dir("never");
  RecordingObserver often_run, never_run;
  simulate(often, often_run, nullptr, Checkpoints{often_dir.path});
  simulate(never, never_run, nullptr, Checkpoints{never_dir.path});
  expect_bit_identical(never_run, often_run, "checkpoints by wall time at every step they may go, and none");
}

}  // namespace
}  // namespace stoss
