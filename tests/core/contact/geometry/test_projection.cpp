#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>

#include "core/contact/geometry/projection.hpp"
#include "tests/core/contact/contact_test_utils.hpp"

namespace stoss::contact {
namespace {
using test::random_nts_state;

// A warped, non-planar segment (not rotated), size ≈ 1.
SegmentNodes warped_segment() {
  SegmentNodes Y;
  Y << 0, 0, 0, 1, 0, 0.1, 1.1, 1, -0.05, 0, 0.9, 0.2;
  return Y;
}

bool finite(const Projection& p) {
  return p.xi.allFinite() && std::isfinite(p.gap) && p.frame.y.allFinite() && p.frame.normal.allFinite();
}

class ProjectionOnWarpedSegment : public ::testing::TestWithParam<unsigned> {};

// The CPP converges and satisfies r_α = 0; x_s − y = g_N n there.
TEST_P(ProjectionOnWarpedSegment, ConvergesToOrthogonalPoint) {
  const test::NtsState s = random_nts_state(GetParam());
  const Projection p = closest_point_projection(s.slave, s.nodes);
  ASSERT_TRUE(p.converged);
  EXPECT_LE(p.iterations, 10);
  const Eigen::Vector3d r = s.slave - p.frame.y;
  EXPECT_LT(projection_residual(p.frame, r).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_LT((r - p.gap * p.frame.normal).norm(), 1e-13);
  EXPECT_GT(p.gap, 0.1);
  EXPECT_TRUE(inside(p.xi, 0));
}

// Starting at the CPP takes a single Newton update (|Δξ| < 1e-13 at once).
TEST_P(ProjectionOnWarpedSegment, RestartAtSolutionTakesOneIteration) {
  const test::NtsState s = random_nts_state(GetParam());
  const Projection p = closest_point_projection(s.slave, s.nodes);
  const Projection again = closest_point_projection(s.slave, s.nodes, p.xi);
  ASSERT_TRUE(again.converged);
  EXPECT_EQ(again.iterations, 1);
  EXPECT_LT((again.xi - p.xi).norm(), 1e-13);
}

INSTANTIATE_TEST_SUITE_P(Seeds, ProjectionOnWarpedSegment, ::testing::Values(1u, 2u, 3u, 4u, 5u));

// Slave points whose exact CPP is a point ξ* on an edge or at a corner, shifted by ±1e-12 (or 0)
// across the boundary, at a positive, zero or negative gap.
struct BoundaryPoint {
  std::string name;
  Eigen::Vector2d xi;       // on the boundary
  Eigen::Vector2d outward;  // direction of the ±1e-12 offset in ξ
};

const BoundaryPoint boundary_points[] = {
    {"edge_xi1_minus", {-1, 0.37}, {-1, 0}},
    {"edge_xi1_plus", {1, -0.61}, {1, 0}},
    {"edge_xi2_minus", {0.13, -1}, {0, -1}},
    {"edge_xi2_plus", {-0.52, 1}, {0, 1}},
    {"corner_1", {-1, -1}, {-1, -1}},
    {"corner_2", {1, -1}, {1, -1}},
    {"corner_3", {1, 1}, {1, 1}},
    {"corner_4", {-1, 1}, {-1, 1}},
    {"corner_3_along_edge", {1, 1}, {1, -1}},
};

using BoundaryCase = std::tuple<BoundaryPoint, double, double>;  // point, offset, gap

class ProjectionAtBoundary : public ::testing::TestWithParam<BoundaryCase> {};

TEST_P(ProjectionAtBoundary, ConvergesOntoTheBoundary) {
  const auto& [point, offset, gap] = GetParam();
  const SegmentNodes Y = warped_segment();
  const Eigen::Vector2d target = point.xi + offset * point.outward;
  const SegmentFrame at = segment_frame(Y, target);
  const Eigen::Vector3d slave = at.y + gap * at.normal;
  const Projection p = closest_point_projection(slave, Y);
  ASSERT_TRUE(p.converged);
  EXPECT_LT((p.xi - target).cwiseAbs().maxCoeff(), 1e-9);
  for (int a = 0; a < 2; ++a) {
    if (point.outward[a] != 0) {
      EXPECT_NEAR(p.xi[a], point.xi[a], 1e-9);
    }
  }
  EXPECT_TRUE(inside(p.xi, 1e-6));
  EXPECT_NEAR(p.gap, gap, 1e-12);
  EXPECT_LT(projection_residual(p.frame, slave - p.frame.y).norm(), 1e-13);
}

std::string boundary_case_name(const ::testing::TestParamInfo<BoundaryCase>& info) {
  const BoundaryPoint& point = std::get<0>(info.param);
  const double offset = std::get<1>(info.param), gap = std::get<2>(info.param);
  const std::string o = offset < 0 ? "in" : offset > 0 ? "out" : "on";
  const std::string g = gap < 0 ? "below" : gap > 0 ? "above" : "at";
  return point.name + "_" + o + "_" + g;
}

INSTANTIATE_TEST_SUITE_P(EdgesAndCorners, ProjectionAtBoundary,
                         ::testing::Combine(::testing::ValuesIn(boundary_points),
                                            ::testing::Values(-1e-12, 0.0, 1e-12),
                                            ::testing::Values(0.1, 0.0, -0.05)),
                         boundary_case_name);

// Far-away, beside, behind and degenerate inputs: a defined outcome, never NaN. The segment is a
// saddle (n·y_{,12} ≈ −0.086), so beyond a few units A of (3.4) is indefinite at ξ = 0 and the CPP
// reports "no projection" at once (det A ≤ 0); far beside it ξ leaves |ξ|_∞ ≤ 10.
struct AwayCase {
  std::string name;
  Eigen::Vector3d slave;
  bool converges;
  bool inside;  // inside(ξ, 1e-6) when converged
};

void PrintTo(const AwayCase& c, std::ostream* os) {
  *os << c.name;
}
void PrintTo(const BoundaryPoint& p, std::ostream* os) {
  *os << p.name;
}

const AwayCase away_cases[] = {
    {"far_above", {0.5, 0.45, 1e3}, false, false},
    {"far_below", {0.5, 0.45, -1e3}, false, false},
    {"above", {0.5, 0.45, 2}, true, true},
    {"behind", {0.5, 0.45, -2}, true, true},
    {"just_behind", {0.5, 0.45, -0.3}, true, true},
    {"beside", {3, 0.4, 0}, true, false},
    {"far_beside", {1e3, 0.4, 0.0}, false, false},
    {"beside_beyond_xi_10", {10, 0.4, 0.5}, false, false},
    {"far_diagonal", {-5e2, 7e2, 3e2}, false, false},
};

class ProjectionAway : public ::testing::TestWithParam<AwayCase> {};

TEST_P(ProjectionAway, HasDefinedOutcome) {
  const AwayCase& c = GetParam();
  const Projection p = closest_point_projection(c.slave, warped_segment());
  EXPECT_TRUE(finite(p));
  EXPECT_LE(p.iterations, ProjectionLimits::max_iterations);
  EXPECT_LE(p.xi.cwiseAbs().maxCoeff(), ProjectionLimits::max_xi);
  EXPECT_EQ(p.converged, c.converges);
  if (p.converged) {
    EXPECT_EQ(inside(p.xi, 1e-6), c.inside);
    EXPECT_LT(projection_residual(p.frame, c.slave - p.frame.y).norm(),
              1e-13 * std::max(1.0, std::abs(p.gap)));
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, ProjectionAway, ::testing::ValuesIn(away_cases),
                         [](const ::testing::TestParamInfo<AwayCase>& info) { return info.param.name; });

TEST(Projection, DegenerateSegmentFailsWithoutNaN) {
  SegmentNodes line;
  line << 0, 0, 0, 1, 0, 0, 2, 0, 0, 1, 0, 0;
  const Projection p = closest_point_projection({0.5, 0.3, 0.2}, line);
  EXPECT_FALSE(p.converged);
  EXPECT_TRUE(finite(p));
}

TEST(Projection, CollapsedSegmentFailsWithoutNaN) {
  const SegmentNodes point = SegmentNodes::Zero();
  const Projection p = closest_point_projection({0.5, 0.3, 0.2}, point);
  EXPECT_FALSE(p.converged);
  EXPECT_EQ(p.iterations, 0);
  EXPECT_TRUE(finite(p));
}

TEST(Projection, InsideUsesTheClosedBox) {
  EXPECT_TRUE(inside({1, -1}, 0));
  EXPECT_TRUE(inside({1 + 1e-7, 0}, 1e-6));
  EXPECT_FALSE(inside({1 + 2e-6, 0}, 1e-6));
  EXPECT_FALSE(inside({0, -1.06}, 0.05));
  EXPECT_TRUE(inside({0, -1.04}, 0.05));
}

}  // namespace
}  // namespace stoss::contact
