// The narrow phase shall assign a slave node to one master face with a defined outcome on shared
// edges and nodes (±1e-12 around them), at the outer boundary, at convex kinks and when no face
// accepts the node (docs/theory.md §3.4).
#include <gtest/gtest.h>

#include <string>
#include <tuple>

#include "core/contact/geometry/assignment.hpp"
#include "core/contact/geometry/broad_phase.hpp"
#include "core/mesh/generators.hpp"

namespace stoss::contact {
namespace {

/// 2 × 2 unit faces on z = 0 (the top of a plate), ids in generator order.
struct Patch {
  mesh::Mesh mesh;
  PairSurfaces s;
  Eigen::VectorXd x;
  std::vector<int> all;
  Patch() {
    mesh.add_body("plate", mesh::box({0, 0, -0.5}, {2, 2, 0}, {2, 2, 1}));
    mesh::BodyMesh probe;  // a one-node "slave surface" so that pair_surfaces has a slave side
    probe.nodes = {Eigen::Vector3d(9, 9, 9), {10, 9, 9}, {10, 10, 9}, {9, 10, 9}};
    probe.surfaces["dot"] = {mesh::Quad{0, 1, 2, 3}};
    mesh.add_body("probe", probe);
    s = pair_surfaces(mesh, "probe/dot", "plate/top");
    x = mesh.reference_positions();
    for (int f = 0; f < static_cast<int>(s.faces.size()); ++f) all.push_back(f);
  }
  /// Faces whose closed (x, y) square contains p, ascending.
  std::vector<int> containing(const Eigen::Vector3d& p) const {
    std::vector<int> out;
    for (int f : all) {
      Box b;
      for (int I : s.faces[f]) b.extend(mesh.nodes[I]);
      if (p.x() >= b.min().x() && p.x() <= b.max().x() && p.y() >= b.min().y() && p.y() <= b.max().y())
        out.push_back(f);
    }
    return out;
  }
};

struct Spot {
  std::string name;
  Eigen::Vector2d at;   ///< (x, y) on the patch
  Eigen::Vector2d dir;  ///< direction of the ±1e-12 offset
};

const Spot spots[] = {
    {"shared_edge", {1, 0.5}, {1, 0}}, {"shared_edge_y", {0.3, 1}, {0, -1}},
    {"shared_node", {1, 1}, {1, 1}},   {"shared_node_skew", {1, 1}, {1, -1}},
    {"outer_edge", {0, 0.7}, {-1, 0}}, {"outer_corner", {2, 2}, {1, 1}},
};

using Case = std::tuple<Spot, double, double>;  // spot, offset, gap
class AssignmentAtEdges : public ::testing::TestWithParam<Case> {};

// The face that contains the point wins; exactly on a shared edge or node the tie goes to the
// lowest face id; a point 1e-12 beyond the outer boundary still belongs to the boundary face.
TEST_P(AssignmentAtEdges, PicksTheFaceHoldingThePoint) {
  const auto& [spot, offset, gap] = GetParam();
  const Patch patch;
  const Eigen::Vector2d xy = spot.at + offset * spot.dir;
  const Eigen::Vector3d p(xy.x(), xy.y(), gap);
  const FaceProjection best = best_face(p, patch.all, patch.s, patch.x);
  ASSERT_TRUE(best.found());
  EXPECT_FALSE(best.extended);
  std::vector<int> holders = patch.containing(p);
  if (holders.empty()) holders = patch.containing(Eigen::Vector3d(spot.at.x(), spot.at.y(), 0));
  ASSERT_FALSE(holders.empty());
  EXPECT_EQ(best.face, holders.front());
  EXPECT_NEAR(best.projection.gap, gap, 1e-14);
  EXPECT_LE(best.projection.xi.cwiseAbs().maxCoeff(), 1 + 1e-11);
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  const double offset = std::get<1>(info.param), gap = std::get<2>(info.param);
  return std::get<0>(info.param).name +
         (offset < 0   ? "_in"
          : offset > 0 ? "_out"
                       : "_on") +
         (gap < 0   ? "_below"
          : gap > 0 ? "_above"
                    : "_at");
}

INSTANTIATE_TEST_SUITE_P(EdgesAndNodes, AssignmentAtEdges,
                         ::testing::Combine(::testing::ValuesIn(spots), ::testing::Values(-1e-12, 0.0, 1e-12),
                                            ::testing::Values(0.1, 0.0, -0.05)),
                         case_name);

TEST(Assignment, BeyondTheOuterEdgeOnlyTheExtendedToleranceAccepts) {
  const Patch patch;
  const FaceProjection near = best_face({-0.01, 0.5, 0.1}, patch.all, patch.s, patch.x);  // ξ¹ = −1.02
  ASSERT_TRUE(near.found());
  EXPECT_TRUE(near.extended);
  EXPECT_FALSE(best_face({-0.2, 0.5, 0.1}, patch.all, patch.s, patch.x).found()) << "ξ¹ = −1.4: no face";
}

TEST(Assignment, ProjectionsThroughTheBodyAreRejected) {
  const Patch patch;  // face size 1 → g_max = 0.5
  EXPECT_TRUE(best_face({0.5, 0.5, -0.4}, patch.all, patch.s, patch.x).found());
  EXPECT_FALSE(best_face({0.5, 0.5, -0.6}, patch.all, patch.s, patch.x).found());
}

TEST(Assignment, SkipLeavesAFaceOutAndEmptyCandidatesFindNothing) {
  const Patch patch;
  const FaceProjection best = best_face({0.5, 0.5, 0.1}, patch.all, patch.s, patch.x);
  ASSERT_TRUE(best.found());
  const FaceProjection other = best_face({0.5, 0.5, 0.1}, patch.all, patch.s, patch.x, best.face);
  EXPECT_FALSE(other.found() && !other.extended) << "no other face holds the point";
  EXPECT_FALSE(best_face({0.5, 0.5, 0.1}, {}, patch.s, patch.x).found());
}

/// Two unit faces meeting along the y axis with slopes ±s: a ridge (convex, s > 0) or a valley.
struct Kink {
  mesh::Mesh mesh;
  PairSurfaces s;
  Eigen::VectorXd x;
  explicit Kink(double drop) {
    mesh::BodyMesh b;
    b.nodes = {
        Eigen::Vector3d(-1, 0, -drop), {0, 0, 0}, {0, 1, 0}, {-1, 1, -drop}, {1, 0, -drop}, {1, 1, -drop}};
    b.surfaces["top"] = {mesh::Quad{0, 1, 2, 3}, mesh::Quad{1, 4, 5, 2}};
    mesh.add_body("roof", b);
    mesh::BodyMesh probe;
    probe.nodes = {Eigen::Vector3d(9, 9, 9), {10, 9, 9}, {10, 10, 9}, {9, 10, 9}};
    probe.surfaces["dot"] = {mesh::Quad{0, 1, 2, 3}};
    mesh.add_body("probe", probe);
    s = pair_surfaces(mesh, "probe/dot", "roof/top");
    x = mesh.reference_positions();
  }
};

TEST(Assignment, ConvexRidgeBlindSpotIsRescuedByTheExtensionOrReportedAsNone) {
  const Kink ridge(0.5);
  const std::vector<int> both{0, 1};
  // Straight above the ridge both feet fall beyond the ridge line: ξ¹ = 1 + 0.8 h on face 0.
  const FaceProjection low = best_face({0, 0.5, 0.02}, both, ridge.s, ridge.x);
  ASSERT_TRUE(low.found());
  EXPECT_TRUE(low.extended);
  EXPECT_EQ(low.face, 0) << "tie in |g_N| and |ξ|_∞: lowest id";
  EXPECT_FALSE(best_face({0, 0.5, 0.3}, both, ridge.s, ridge.x).found()) << "ξ¹ = 1.24: no contact element";
}

TEST(Assignment, ConcaveValleyTakesTheCloserFace) {
  const Kink valley(-0.5);
  const std::vector<int> both{0, 1};
  const Eigen::Vector3d p(-0.1, 0.5, 0.2);
  const FaceProjection best = best_face(p, both, valley.s, valley.x);
  ASSERT_TRUE(best.found());
  const FaceProjection other = project_on(p, 1 - best.face, valley.s, valley.x);
  EXPECT_LT(std::abs(best.projection.gap), std::abs(other.projection.gap));
  EXPECT_EQ(best.face, 0);
}

}  // namespace
}  // namespace stoss::contact
