// (V9) nodes_inside_other_body (docs/results.md, "Verdict"): two boxes of 2 × 2 × 2 elements of edge 0.5,
// overlapping, apart, touching and pressed together by less than the margin, with counts worked out by hand.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "core/mesh/generators.hpp"
#include "core/run/checks.hpp"

namespace stoss::run {
namespace {

/// Box a = [0, 1]³ and box b = [0, 1]³ moved by `shift`, each 2 × 2 × 2 elements.
mesh::Mesh two_boxes(const Eigen::Vector3d& shift) {
  mesh::Mesh m;
  m.add_body("a", mesh::box({0, 0, 0}, {1, 1, 1}, {2, 2, 2}));
  m.add_body("b", mesh::box(shift, shift + Eigen::Vector3d(1, 1, 1), {2, 2, 2}));
  return m;
}

Eigen::VectorXd positions(const mesh::Mesh& m, const Eigen::Affine3d& motion = Eigen::Affine3d::Identity()) {
  Eigen::VectorXd x(3 * m.node_count());
  for (int n = 0; n < m.node_count(); ++n) x.segment<3>(3 * n) = motion * m.nodes[n];
  return x;
}

TEST(NodesInsideOtherBody, OverlappingBoxesCountTheNodesEachHoldsOfTheOther) {
  // b = [0.6, 1.6] × [0.1, 1.1]²: b's nodes x = 0.6, y, z ∈ {0.1, 0.6} lie in a (4), a's nodes x = 1,
  // y, z ∈ {0.5, 1} lie in b (4), each at |ξ| = 0.6 of the element that holds it.
  const mesh::Mesh m = two_boxes({0.6, 0.1, 0.1});
  EXPECT_EQ(nodes_inside_other_body(m, positions(m)), 8);
}

TEST(NodesInsideOtherBody, TheCountFollowsTheDeformedPositionsNotTheReference) {
  const mesh::Mesh m = two_boxes({0.6, 0.1, 0.1});
  // A rigid motion keeps the count: element boxes grow, the inverse map still finds |ξ| = 0.6.
  const Eigen::Affine3d motion =
      Eigen::Translation3d(3, -2, 1) * Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  EXPECT_EQ(nodes_inside_other_body(m, positions(m, motion)), 8);
  // b moved out of a in x (its reference still overlaps): none.
  Eigen::VectorXd x = positions(m);
  for (int n = m.bodies[1].node_begin; n < m.bodies[1].node_end; ++n) x[3 * n] += 2;
  EXPECT_EQ(nodes_inside_other_body(m, x), 0);
}

TEST(NodesInsideOtherBody, BoxesApartHoldNone) {
  const mesh::Mesh m = two_boxes({1.5, 0, 0});
  EXPECT_EQ(nodes_inside_other_body(m, positions(m)), 0);
}

TEST(NodesInsideOtherBody, NodesExactlyOnTheOtherBodysFaceAreNotInside) {
  const mesh::Mesh m = two_boxes({1, 0, 0});  // b's face x = 1 lies on a's face x = 1, node on node
  EXPECT_EQ(nodes_inside_other_body(m, positions(m)), 0);
  const mesh::Mesh offset = two_boxes({1, 0.25, 0.25});  // b's nodes in the middle of a's faces
  EXPECT_EQ(nodes_inside_other_body(offset, positions(offset)), 0);
}

TEST(NodesInsideOtherBody, APenetrationWithinTheMarginIsNotInsideADeeperOneIs) {
  // 1 − |ξ| = depth / (element edge / 2) = 0.01 / 0.25 = 0.04 < inside_margin.
  const mesh::Mesh shallow = two_boxes({0.99, 0, 0});
  EXPECT_EQ(nodes_inside_other_body(shallow, positions(shallow)), 0);
  // At depth 0.1: b's node (0.9, 0.5, 0.5) lies on interior faces of a (still inside a), and a's node
  // (1, 0.5, 0.5) on interior faces of b; the others lie on a boundary face (y or z = 0 or 1).
  const mesh::Mesh deep = two_boxes({0.9, 0, 0});
  EXPECT_EQ(nodes_inside_other_body(deep, positions(deep)), 2);
}

TEST(NodesInsideOtherBody, RunChecksAddsItWithBoundZeroForTwoBodiesOnly) {
  model::Model m;
  m.mesh = two_boxes({0.6, 0.1, 0.1});
  m.time.scheme = model::Scheme::energy_momentum;
  const auto checks = run_checks(m, model::Summary{}, positions(m.mesh));
  const auto it = std::find_if(checks.begin(), checks.end(),
                               [](const model::Check& c) { return c.name == "nodes_inside_other_body"; });
  ASSERT_NE(it, checks.end());
  EXPECT_EQ(it->value, 8);
  EXPECT_EQ(it->bound, 0);
  EXPECT_FALSE(it->passed);
  EXPECT_EQ(verdict_of(checks), "suspect");
  model::Model one;
  one.mesh.add_body("a", mesh::box({0, 0, 0}, {1, 1, 1}, {2, 2, 2}));
  for (const model::Check& c : run_checks(one, model::Summary{}, positions(one.mesh)))
    EXPECT_NE(c.name, "nodes_inside_other_body");
}

}  // namespace
}  // namespace stoss::run
