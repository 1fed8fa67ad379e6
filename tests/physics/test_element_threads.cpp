// The element loops run on parallel::worker_threads() threads (STOSS_THREADS, default every core): each
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
    parallel::set_worker_threads(threads);
    summary = simulate(m, r);
    parallel::set_worker_threads(0);
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

// The mortar term computes its face pairs on the same threads and sums them in pair order (docs/theory.md
// §4.7.1): the seed's example with mortar through its first contact gives the same bits on 1, 2 and 3.
TEST(ElementThreads, MortarContactGivesTheSameBitsOnOneTwoAndThreeThreads) {
  model::Model m = scene::load_file(std::string(STOSS_SOURCE_DIR) + "/api/examples/hollow_ball_plate.json");
  m.contact.at(0).discretization = model::Discretization::mortar;
  m.contact.at(0).master_surface = model::MasterSurface::faceted;  // as the scene resolves it for mortar
  m.time.end = 0.4;
  const ThreadedRun one(m, 1), two(m, 2), three(m, 3);
  ASSERT_TRUE(one.summary.completed);
  const auto active = one.r.series("active_contacts");
  // One active slave node: its four slave faces against the plate's faces, pairs for every thread.
  EXPECT_GE(*std::max_element(active.begin(), active.end()), 1) << "the contact phase is covered";
  expect_same_bits(one, two);
  expect_same_bits(one, three);
}

}  // namespace
}  // namespace stoss
