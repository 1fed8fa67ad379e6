#include <gtest/gtest.h>

#include "core/contact/geometry/projection.hpp"
#include "core/contact/lagrange/constraints.hpp"
#include "core/contact/lagrange/invariants.hpp"
#include "tests/core/contact/contact_test_utils.hpp"

namespace stoss::contact {
namespace {
using test::fd_jacobian;
using test::fd_step;
using test::relative_error;

class Constraints : public ::testing::TestWithParam<unsigned> {
 protected:
  void SetUp() override {
    m = test::random_mixed_state(GetParam());
    pi = invariants(m.q_n, m.f3);
  }
  test::MixedState m;
  Vector17 pi;
};

// With d = n and ξ = CPP: g = (g_N − f_3, 0, 0, 0, 0, 0).
TEST_P(Constraints, AtTheClosestPointOnlyTheGapRemains) {
  const test::NtsState s = test::random_nts_state(GetParam());
  const Projection p = closest_point_projection(s.slave, s.nodes);
  ASSERT_TRUE(p.converged);
  const Vector6 g = constraints(invariants(mixed_coordinates(s.slave, s.nodes, p.frame.normal, p.xi), m.f3));
  Vector6 expected = Vector6::Zero();
  expected[0] = p.gap - m.f3;
  EXPECT_LT((g - expected).cwiseAbs().maxCoeff(), 1e-12);
}

// Off the CPP the right-hand sides of (4.3) hold: (x_s − y(ξ))·d − f_3, τ_α·d, ½(d·d − 1),
// (x_s − y(ξ))·τ_α.
TEST_P(Constraints, MatchTheirGeometricMeaning) {
  const Vector15 x = m.q_n.head<15>();
  const Eigen::Vector3d d = m.q_n.segment<3>(MixedLayout::director);
  const SegmentFrame f = segment_frame(segment_nodes(x), m.q_n.segment<2>(MixedLayout::xi));
  const Eigen::Vector3d r = slave_position(x) - f.y;
  Vector6 expected;
  expected << r.dot(d) - m.f3, f.tau1.dot(d), f.tau2.dot(d), 0.5 * (d.dot(d) - 1), r.dot(f.tau1),
      r.dot(f.tau2);
  EXPECT_LT((constraints(pi) - expected).cwiseAbs().maxCoeff(), 1e-14);
}

TEST_P(Constraints, GradientMatchesFiniteDifferences) {
  EXPECT_LT(relative_error(constraint_gradient(pi), fd_jacobian(constraints, pi, fd_step)), 1e-8);
}

TEST_P(Constraints, HessiansMatchFiniteDifferences) {
  const std::array<Matrix17, 6> H = constraint_hessians(pi);
  for (int k = 0; k < 6; ++k) {
    const auto row = [k](const Vector17& p) { return Vector17(constraint_gradient(p).row(k).transpose()); };
    const Matrix17 fd = fd_jacobian(row, pi, fd_step);
    if (k == 3) {
      EXPECT_TRUE(H[k].isZero(0));
      EXPECT_LT(fd.norm(), 1e-12);
      continue;
    }
    EXPECT_LT(relative_error(H[k], fd), 1e-8) << "k = " << k;
    EXPECT_EQ((H[k] - H[k].transpose()).norm(), 0.0) << "k = " << k;
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, Constraints, ::testing::Values(1u, 2u, 3u, 4u));

}  // namespace
}  // namespace stoss::contact
