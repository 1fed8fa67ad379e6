// The step controller (docs/theory.md §2.7) shall accept a step whose local error estimate (2.16)/(2.17) is
// within its share of time.tolerance (2.18) and grow the next one by at most 2×, reject one beyond it with
// the reason and a smaller proposal, hold a contact's frozen gap to its share, keep its proposals in
// [min_step, max_step], and give up only below min_step.
#include <gtest/gtest.h>

#include <cmath>

#include "core/run/step_control.hpp"

namespace stoss::run {
namespace {

model::TimeSpec adaptive_time(model::Scheme scheme = model::Scheme::energy_momentum) {
  model::TimeSpec t;
  t.scheme = scheme;
  t.step = 0.01;
  t.end = 1;
  t.tolerance = 1e-3;
  t.min_step = 1e-4;
  t.max_step = 0.05;
  return t;
}

/// One node whose mean acceleration over the step is `a` (the midpoint schemes' s.a, scheme.hpp).
time::State with_acceleration(double a) {
  time::State s;
  s.x = s.v = Eigen::VectorXd::Zero(3);
  s.a = Eigen::Vector3d(a, 0, 0);
  return s;
}

/// A first step (no estimate for a midpoint-type scheme: s.a is 0 before it) that sets h_{n−1} = h.
StepController after_first_step(const model::TimeSpec& t, double h) {
  static const std::unique_ptr<time::Scheme> scheme = time::make_scheme(t);
  StepController c(t, *scheme);
  EXPECT_TRUE(c.judge(h, with_acceleration(0), with_acceleration(0), {}).accepted);
  return c;
}

TEST(StepControl, AStepWithinItsShareIsAcceptedAndTheNextGrowsByTheCubeRootOfTheRatio) {
  StepController c = after_first_step(adaptive_time(), 0.01);
  // (2.16): ê = h³/12 · |Δā| / h_avg = 1e-6/12 · 3 / 0.01 = 2.5e-5 against 0.05 × 1e-3 = 5e-5.
  const StepVerdict v = c.judge(0.01, with_acceleration(1), with_acceleration(4), {});
  EXPECT_TRUE(v.accepted);
  EXPECT_NEAR(v.error, 2.5e-5, 1e-15);
  EXPECT_NEAR(v.target, 5e-5, 1e-18);
  EXPECT_NEAR(c.state().next_step, 0.01 * 0.8 * std::cbrt(2.0), 1e-15);  // (2.19)
  EXPECT_EQ(c.state().previous_step, 0.01);
}

TEST(StepControl, AStepBeyondItsShareIsRejectedWithItsReasonAndASmallerProposal) {
  StepController c = after_first_step(adaptive_time(), 0.01);
  const StepVerdict v = c.judge(0.01, with_acceleration(0), with_acceleration(240), {});  // ê = 2e-3
  EXPECT_FALSE(v.accepted);
  EXPECT_EQ(v.reason.rfind("error: estimate 0.002 > 5e-05", 0), 0u) << v.reason;
  EXPECT_NEAR(c.state().next_step, 0.01 * 0.8 * std::cbrt(5e-5 / 2e-3), 1e-15);
  EXPECT_EQ(c.state().previous_step, 0.01) << "a rejected try is no previous step";
}

// The first step has no previous step: a(0) stands in for ā_{−½} at h_{−1} = 0, so a first step far
// above what the tolerance needs is rejected too.
TEST(StepControl, TheFirstStepIsJudgedAgainstTheInitialAcceleration) {
  const model::TimeSpec t = adaptive_time();
  const std::unique_ptr<time::Scheme> scheme = time::make_scheme(t);
  StepController c(t, *scheme, Eigen::VectorXd::Zero(3));
  const StepVerdict v = c.judge(0.01, with_acceleration(0), with_acceleration(240), {});
  EXPECT_NEAR(v.error, 1e-6 / 12 * 240 / 0.005, 1e-15);  // (2.16) with h_avg = h/2
  EXPECT_FALSE(v.accepted);
}

TEST(StepControl, NewmarkSchemesUseTheZienkiewiczXieEstimate) {
  const model::TimeSpec t = adaptive_time(model::Scheme::hht);
  const std::unique_ptr<time::Scheme> scheme = time::make_scheme(t);
  StepController c(t, *scheme);
  // (2.17) with HHT's β = (1 − α)²/4 at α = −0.05: ê = |β − 1/6| h² |a_{n+1} − a_n|, from the first step on.
  const double beta = 1.05 * 1.05 / 4, error = std::abs(beta - 1.0 / 6) * 1e-4 * 0.2;
  const StepVerdict v = c.judge(0.01, with_acceleration(0.1), with_acceleration(0.3), {});
  EXPECT_NEAR(v.error, error, 1e-18);
  EXPECT_TRUE(v.accepted);
}

TEST(StepControl, AContactsFrozenGapBeyondItsShareRejectsTheStepNamingThePair) {
  StepController c = after_first_step(adaptive_time(), 0.01);
  ContactEvents events{6e-4, 3, "contact ball/outer on plate/top"};  // above 0.5 × TOL
  const StepVerdict v = c.judge(0.01, with_acceleration(0), with_acceleration(1e3), events);
  EXPECT_FALSE(v.accepted);
  EXPECT_EQ(v.reason.rfind("contact: contact ball/outer on plate/top, 3 nodes changed state", 0), 0u)
      << v.reason;
  EXPECT_LT(c.state().next_step, 0.01 * 0.5 / 0.6);  // first order in h: h · 0.8 · (share / gap)
  events.offset = 4e-4;                              // within it: accepted, whatever the acceleration jump
  EXPECT_TRUE(c.judge(0.005, with_acceleration(0), with_acceleration(1e3), events).accepted);
  EXPECT_FALSE(c.state().has_history) << "the next step's estimate would see the impact's impulse";
}

TEST(StepControl, ProposalsStayWithinMinAndMaxStepAndTheLastTryIsAtMinStep) {
  StepController c = after_first_step(adaptive_time(), 0.04);
  c.judge(0.04, with_acceleration(0), with_acceleration(0), {});  // no error at all: 2×, clamped
  EXPECT_EQ(c.state().next_step, 0.05);
  c.newton_failed(2e-4);  // proposes 5e-5 < min_step: one last try at min_step, then none
  EXPECT_TRUE(c.can_retry(2e-4));
  EXPECT_EQ(c.state().next_step, 1e-4);
  c.newton_failed(1e-4);
  EXPECT_FALSE(c.can_retry(1e-4));
}

TEST(StepControl, AStepLandsOnTheNextFrameTimeWithoutLeavingASliver) {
  StepController c = after_first_step(adaptive_time(), 0.01);  // proposal 0.01
  EXPECT_EQ(c.step_to(0.0, 0.5), 0.01);
  EXPECT_EQ(c.step_to(0.0, 0.015), 0.0075);       // within two proposals: two like steps
  EXPECT_EQ(c.step_to(0.0, 0.01), 0.01);          // exactly the rest
  EXPECT_EQ(c.step_to(0.492, 0.5), 0.5 - 0.492);  // the rest, when shorter
}

}  // namespace
}  // namespace stoss::run
