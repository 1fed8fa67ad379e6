#include <gtest/gtest.h>

#include <tuple>

#include "core/contact/lagrange/elements/mixed_element.hpp"
#include "tests/core/contact/contact_test_utils.hpp"

namespace stoss::contact {
namespace {
using test::fd_jacobian;
using test::fd_step;
using test::relative_error;

using Case = std::tuple<unsigned, double>;  // seed, |q_{n+1} − q_n|

class MixedElement : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    const auto [seed, step] = GetParam();
    m = test::random_mixed_state(seed, step);
    e = mixed_element(m.q_n, m.q_1, m.lambda, m.f3, m.h);
  }
  MixedResult at(const Vector20& q_1, const Vector6& lambda) const {
    return mixed_element(m.q_n, q_1, lambda, m.f3, m.h);
  }
  test::MixedState m;
  MixedResult e;
};

// (4.10) against central differences of (4.9); §6.1 bound 1e-6.
TEST_P(MixedElement, KqqMatchesFiniteDifferences) {
  const auto Rq = [&](const Vector20& q) { return at(q, m.lambda).Rq; };
  EXPECT_LT(relative_error(e.Kqq, fd_jacobian(Rq, m.q_1, fd_step)), 1e-6);
}

TEST_P(MixedElement, KqlMatchesFiniteDifferences) {
  const auto Rq = [&](const Vector6& lambda) { return at(m.q_1, lambda).Rq; };
  EXPECT_LT(relative_error(e.Kql, fd_jacobian(Rq, m.lambda, fd_step)), 1e-6);
}

TEST_P(MixedElement, KlqMatchesFiniteDifferences) {
  const auto Rl = [&](const Vector20& q) { return at(q, m.lambda).Rl; };
  EXPECT_LT(relative_error(e.Klq, fd_jacobian(Rl, m.q_1, fd_step)), 1e-6);
}

// Translation invariance: the five nodal forces sum to zero.
TEST_P(MixedElement, NodalForcesSumToZero) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int node = 0; node < 5; ++node) sum += e.Rq.segment<3>(3 * node);
  EXPECT_LT(sum.norm(), 1e-13 * e.Rq.head<15>().norm());
}

// Rotation invariance in (x, d): Σ x_m × F + d_m × R_d = 0.
TEST_P(MixedElement, TorqueVanishes) {
  const Vector20 q_m = 0.5 * (m.q_n + m.q_1);
  Eigen::Vector3d torque =
      q_m.segment<3>(MixedLayout::director).cross(e.Rq.segment<3>(MixedLayout::director));
  for (int node = 0; node < 5; ++node) torque += q_m.segment<3>(3 * node).cross(e.Rq.segment<3>(3 * node));
  double scale = 0;
  for (int node = 0; node < 6; ++node)
    scale += q_m.segment<3>(3 * node).norm() * e.Rq.segment<3>(3 * node).norm();
  EXPECT_LT(torque.norm(), 1e-12 * scale);
}

// Element energy identity (key step of (4.11)): Rq·Δq = h λ·(g(π_{n+1}) − g(π_n)).
TEST_P(MixedElement, WorkEqualsMultiplierTimesConstraintChange) {
  const double work = e.Rq.dot(m.q_1 - m.q_n);
  const double expected = m.h * m.lambda.dot(e.Rl - e.g_n);
  EXPECT_LE(std::abs(work - expected), 1e-13 * std::max(std::abs(expected), m.h * m.lambda.norm() * 1e-2));
}

TEST_P(MixedElement, ConstraintResidualsAreGAtBothEnds) {
  EXPECT_EQ(e.Rl, constraints(invariants(m.q_1, m.f3)));
  EXPECT_EQ(e.g_n, constraints(invariants(m.q_n, m.f3)));
}

INSTANTIATE_TEST_SUITE_P(SeedsAndSteps, MixedElement,
                         ::testing::Combine(::testing::Values(1u, 2u, 3u, 4u),
                                            ::testing::Values(0.05, 1e-4, 0.0)));

}  // namespace
}  // namespace stoss::contact
