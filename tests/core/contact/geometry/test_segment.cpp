#include <gtest/gtest.h>

#include "core/contact/geometry/segment.hpp"
#include "tests/core/contact/contact_test_utils.hpp"

namespace stoss::contact {
namespace {
using test::fd_jacobian;
using test::random_nts_state;
using test::relative_error;

TEST(Segment, ShapeFunctionsArePartitionOfUnity) {
  for (const Eigen::Vector2d& xi :
       {Eigen::Vector2d(0, 0), Eigen::Vector2d(0.3, -0.7), Eigen::Vector2d(1.2, 1)}) {
    const BilinearShape s = bilinear_shape(xi);
    EXPECT_NEAR(s.N.sum(), 1.0, 1e-15);
    EXPECT_NEAR(s.dN.col(0).sum(), 0.0, 1e-15);
    EXPECT_NEAR(s.dN.col(1).sum(), 0.0, 1e-15);
    EXPECT_NEAR(s.d2N12.sum(), 0.0, 1e-15);
  }
}

TEST(Segment, ShapeFunctionsInterpolateTheCorners) {
  const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (int K = 0; K < 4; ++K) {
    const BilinearShape s = bilinear_shape({corners[K][0], corners[K][1]});
    for (int L = 0; L < 4; ++L) EXPECT_EQ(s.N[L], K == L ? 1.0 : 0.0);
  }
}

TEST(Segment, TangentsAndTwistMatchFiniteDifferences) {
  const test::NtsState s = random_nts_state(7);
  const Eigen::Vector2d xi(0.21, -0.43);
  const SegmentFrame f = segment_frame(s.nodes, xi);
  const auto y = [&](const Eigen::Vector2d& z) { return segment_frame(s.nodes, z).y; };
  const auto tau1 = [&](const Eigen::Vector2d& z) { return segment_frame(s.nodes, z).tau1; };
  const Eigen::Matrix<double, 3, 2> dy = fd_jacobian(y, xi, 1e-6);
  EXPECT_LT(relative_error(f.tau1, dy.col(0)), 1e-9);
  EXPECT_LT(relative_error(f.tau2, dy.col(1)), 1e-9);
  EXPECT_LT(relative_error(f.y12, fd_jacobian(tau1, xi, 1e-6).col(1)), 1e-8);
}

TEST(Segment, FrameIsConsistent) {
  const test::NtsState s = random_nts_state(8);
  const SegmentFrame f = segment_frame(s.nodes, {0.5, 0.1});
  EXPECT_NEAR(f.normal.norm(), 1.0, 1e-15);
  EXPECT_NEAR(f.normal.dot(f.tau1), 0.0, 1e-15);
  EXPECT_NEAR(f.normal.dot(f.tau2), 0.0, 1e-15);
  EXPECT_GT(f.normal.dot(f.tau1.cross(f.tau2)), 0.0);
  EXPECT_LT((f.metric * f.metric_inv - Eigen::Matrix2d::Identity()).norm(), 1e-14);
  EXPECT_NEAR(f.metric(0, 1), f.tau1.dot(f.tau2), 1e-15);
}

TEST(Segment, DegenerateSegmentGivesZeroNormalNotNaN) {
  SegmentNodes line;
  line << 0, 0, 0, 1, 0, 0, 2, 0, 0, 1, 0, 0;  // all nodes on the x axis
  const SegmentFrame f = segment_frame(line, {0.2, 0.3});
  EXPECT_TRUE(f.normal.isZero(0));
  EXPECT_TRUE(f.metric_inv.allFinite());
  EXPECT_TRUE(f.y.allFinite());
}

}  // namespace
}  // namespace stoss::contact
