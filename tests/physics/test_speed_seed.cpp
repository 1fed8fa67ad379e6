// Issue 26: the levers that make the seed's example faster keep its answers. The run (with a checkpoint
// store, as `stoss run` has, so the checkpoint schedule's refreshes happen) is compared with the numbers of
// main before the levers, to the scale of the Newton tolerance (1e-10 per step): energy and momenta to
// 1e-9 of their size, positions of the last frame to 1e-8 (the model is ~6 long). No wall time is asserted.
//
// Reference numbers: `stoss run api/examples/hollow_ball_plate.json -o /tmp/seed_ref` of da4188b, whose 157
// digests equal the baseline's (bench/check_bit_identity.sh) as main's 7b8fb2f does, read with h5py:
// /series/total_energy[0, 50, 100], /series/linear_momentum[100], /series/angular_momentum[100] and
// /frames/20/position (mean over nodes; nodes 0, 760, 1520).
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <filesystem>

#include "../core/recording_observer.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"

namespace stoss {
namespace {

using testing::RecordingObserver;

const RecordingObserver& seed_run() {
  static const RecordingObserver run = [] {
    const model::Model m =
        scene::load_file(std::string(STOSS_SOURCE_DIR) + "/api/examples/hollow_ball_plate.json");
    const std::filesystem::path store =
        std::filesystem::temp_directory_path() / ("test_speed_seed_" + std::to_string(::getpid()));
    RecordingObserver r;
    simulate(m, r, nullptr, Checkpoints{store, false});
    std::filesystem::remove_all(store);
    return r;
  }();
  return run;
}

TEST(SpeedSeed, EnergyAndMomentaAreThoseOfMainToTheNewtonToleranceScale) {
  const RecordingObserver& r = seed_run();
  ASSERT_TRUE(r.summary.completed);
  ASSERT_EQ(r.summary.steps, 100);
  const std::vector<double> H = r.series("total_energy");
  ASSERT_EQ(H.size(), 101u);
  const double H0 = 1.9837552512440093;
  EXPECT_NEAR(H[0], H0, 1e-12);
  EXPECT_NEAR(H[50], 1.983755251238123, 1e-9 * H0);
  EXPECT_NEAR(H[100], 1.9837552512153744, 1e-9 * H0);
  const std::array<double, 3> L = {2.3303655148155036e-14, 1.9837552512440235, -1.983755251244015},
                              J = {-2.5788818266115934, 7.011752289898254e-15, -1.2987115723117615e-15};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(r.series("linear_momentum", k).back(), L[k], 1e-9 * 2.8) << "component " << k;
    EXPECT_NEAR(r.series("angular_momentum", k).back(), J[k], 1e-9 * 2.6) << "component " << k;
  }
}

TEST(SpeedSeed, TheLastFramesPositionsAreThoseOfMainToTheNewtonToleranceScale) {
  const RecordingObserver& r = seed_run();
  ASSERT_FALSE(r.frames.empty());
  const model::Frame& last = r.frames.back();
  ASSERT_DOUBLE_EQ(last.time, 1.0);
  ASSERT_EQ(last.position.size(), 3 * 1521);
  const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> x(last.position.data(), 3, 1521);
  const Eigen::Vector3d mean = x.rowwise().mean();
  const Eigen::Vector3d mean_of_main(1.779568529938285e-15, 0.7147994210855645, 0.11865610221092295);
  EXPECT_LT((mean - mean_of_main).norm(), 1e-8);
  const std::array<std::pair<int, Eigen::Vector3d>, 3> nodes_of_main = {{
      {0, {0.4619401124731129, 0.5339458411443421, 0.4255517581624471}},
      {760, {-1.0020733272667064, 0.0016651588231721803, -0.5857027485237605}},
      {1520, {1.9949916048943364, 2.494426522780417, -0.2771796609943722}},
  }};
  for (const auto& [node, position] : nodes_of_main)
    EXPECT_LT((x.col(node) - position).norm(), 1e-8) << "node " << node;
}

}  // namespace
}  // namespace stoss
