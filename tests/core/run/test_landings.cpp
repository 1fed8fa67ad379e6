// Where a run's steps land and when frames are due (core/run/landings.hpp), and the step forces of
// substeps (core/run/step_forces.hpp).
#include <gtest/gtest.h>

#include "core/run/landings.hpp"
#include "core/run/step_forces.hpp"

namespace stoss::run {
namespace {

model::Model model_with(double end, std::optional<double> interval, int every = 1) {
  model::Model m;
  m.time.step = 0.1;
  m.time.end = end;
  m.output.interval = interval;
  m.output.every = every;
  return m;
}

TEST(Landings, AFixedStepTakesTheRestWhenItIsWithinRoundOffOfAStepOrShorter) {
  EXPECT_DOUBLE_EQ(fixed_step_to(0.1, 0.0, 1.0), 0.1);
  EXPECT_DOUBLE_EQ(fixed_step_to(0.1, 0.95, 1.0), 1.0 - 0.95);
  EXPECT_EQ(fixed_step_to(0.1, 0.9, 1.0 + 1e-8), 1.0 + 1e-8 - 0.9);  // within 1e-6 of a step: the rest
}

TEST(Landings, TheEndSnapsToTheLastFrameTimeWithinRoundOffOnly) {
  EXPECT_EQ(Landings(model_with(0.3 + 1e-12, 0.1)).end(), 3 * 0.1);
  EXPECT_EQ(Landings(model_with(0.35, 0.1)).end(), 0.35);
  EXPECT_EQ(Landings(model_with(0.35, std::nullopt)).end(), 0.35);
}

TEST(Landings, FramesAtAnIntervalMoveOnOnlyWhenAStepLandedOrTheRunEnded) {
  Landings landings(model_with(0.25, 0.1));
  EXPECT_DOUBLE_EQ(landings.next(), 0.1);
  EXPECT_FALSE(landings.frame_due(1, false, false));
  EXPECT_DOUBLE_EQ(landings.next(), 0.1);
  EXPECT_TRUE(landings.frame_due(2, false, true));
  EXPECT_DOUBLE_EQ(landings.next(), 0.2);
  EXPECT_TRUE(landings.frame_due(3, false, true));
  EXPECT_DOUBLE_EQ(landings.next(), 0.25);  // the end, not 0.3
  landings.set_next_frame(1);               // as a resumed run sets it from its frame count
  EXPECT_DOUBLE_EQ(landings.next(), 0.1);
}

TEST(Landings, WithoutAnIntervalFramesFollowEveryAndTheLastStep) {
  Landings landings(model_with(1.0, std::nullopt, 3));
  EXPECT_TRUE(landings.frame_due(3, false, false));
  EXPECT_FALSE(landings.frame_due(4, false, false));
  EXPECT_TRUE(landings.frame_due(4, true, false));
  EXPECT_DOUBLE_EQ(landings.next(), 1.0);
}

TEST(StepForces, SubstepsAreWeightedByTheirStepSoTheForceTimesHIsTheirImpulse) {
  StepForces forces;
  forces.add(0.25, {Eigen::Vector3d(4, 0, 0)});
  EXPECT_EQ(forces.step_forces()[0], Eigen::Vector3d(4, 0, 0));  // one substep: its force exactly
  forces.add(0.75, {Eigen::Vector3d(0, 8, 0)});
  const Eigen::Vector3d f = forces.step_forces()[0];
  EXPECT_NEAR((f * 1.0 - Eigen::Vector3d(0.25 * 4, 0.75 * 8, 0)).norm(), 0.0, 1e-15);
  forces.clear();
  EXPECT_TRUE(forces.step_forces().empty());
}

}  // namespace
}  // namespace stoss::run
