// The element loops run on fem::element_threads() threads (STOSS_THREADS, default every core): each
// thread computes whole elements and one thread sums them in element order, so a run gives the same
// bits at every thread count, 1 included — stronger than agreeing to the Newton tolerance (issue 12).
// The seed's example (944 hex8: two chunks of 512 tangents) for 36 steps, 6 of them in contact.
#include <gtest/gtest.h>

#include <algorithm>

#include "../core/recording_observer.hpp"
#include "core/fem/assembly.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"

namespace stoss {
namespace {

struct ThreadedRun {
  testing::RecordingObserver r;
  model::Summary summary;
  ThreadedRun(const model::Model& m, int threads) {
    fem::set_element_threads(threads);
    summary = simulate(m, r);
    fem::set_element_threads(0);
  }
};

void expect_same_bits(const ThreadedRun& a, const ThreadedRun& b) {
  ASSERT_EQ(a.r.rows.size(), b.r.rows.size());
  for (const char* name :
       {"total_energy", "kinetic_energy", "strain_energy", "active_contacts", "newton_iterations"})
    EXPECT_EQ(a.r.series(name), b.r.series(name)) << name;
  ASSERT_EQ(a.r.frames.size(), b.r.frames.size());
  EXPECT_EQ(a.r.frames.back().position, b.r.frames.back().position);
  EXPECT_EQ(a.r.frames.back().velocity, b.r.frames.back().velocity);
  EXPECT_EQ(a.summary.newton_iterations, b.summary.newton_iterations);
}

TEST(ElementThreads, TheSeedExampleGivesTheSameBitsOnOneTwoAndThreeThreads) {
  model::Model m = scene::load_file(std::string(STOSS_SOURCE_DIR) + "/api/examples/hollow_ball_plate.json");
  ASSERT_GT(m.mesh.element_count(), 512) << "more than one chunk of tangents";
  m.time.end = 0.36;  // 36 steps of 0.01: the ball reaches the plate at step 31
  const ThreadedRun one(m, 1), two(m, 2), two_again(m, 2), three(m, 3);
  ASSERT_TRUE(one.summary.completed);
  const auto active = one.r.series("active_contacts");
  EXPECT_GT(*std::max_element(active.begin(), active.end()), 0) << "the contact phase is covered";
  expect_same_bits(two, two_again);
  expect_same_bits(one, two);
  expect_same_bits(one, three);
}

TEST(ElementThreads, SetElementThreadsOverridesAndZeroRestoresTheDefault) {
  const int default_threads = fem::element_threads();
  EXPECT_GE(default_threads, 1);
  fem::set_element_threads(3);
  EXPECT_EQ(fem::element_threads(), 3);
  fem::set_element_threads(0);
  EXPECT_EQ(fem::element_threads(), default_threads);
}

}  // namespace
}  // namespace stoss
