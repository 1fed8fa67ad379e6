// The smooth master surface (docs/smooth_master_surface.md §2) shall be a partition of unity, reproduce
// a flat uniform grid exactly, be C¹ (in fact C²) across patch edges in the interior and at a rim,
// refuse extraordinary vertices and non-manifold surfaces by name, and its CPP (§3.1) shall find the
// brute-force closest point.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/contact/geometry/patch_projection.hpp"
#include "core/contact/geometry/smooth_surface.hpp"
#include "tests/core/contact/smooth_test_utils.hpp"

namespace stoss::contact {
namespace {

using test::Grid;

Eigen::Vector3d point(const TensorPatch& p, const Eigen::VectorXd& x, const Eigen::Vector2d& xi) {
  return patch_frame(p, x, xi).y;
}

TEST(SmoothSurface, BasisIsAPartitionOfUnityWithZeroSumDerivatives) {
  const Grid g = Grid::curved(5, 4);
  const SmoothSurface s = smooth_surface(g.faces);
  ASSERT_TRUE(s.ok()) << s.problem;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.1, 1.1);
  for (const TensorPatch& p : s.patches) {
    const BasisValues<double> b = patch_values(p, u(rng), u(rng));
    double sum = 0, sum1 = 0, sum2 = 0;
    for (int K = 0; K < p.size(); ++K) sum += b.N[K], sum1 += b.N1[K], sum2 += b.N2[K];
    EXPECT_NEAR(sum, 1, 1e-14);
    EXPECT_NEAR(sum1, 0, 1e-14);
    EXPECT_NEAR(sum2, 0, 1e-14);
  }
}

TEST(SmoothSurface, InteriorPatchHasSixteenNodesRimPatchesFewer) {
  const Grid g = Grid::curved(5, 5);
  const SmoothSurface s = smooth_surface(g.faces);
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s.patches[g.face(1, 1)].size(), 16);  // all neighbours real
  EXPECT_EQ(s.patches[g.face(0, 1)].size(), 12);  // one rim edge
  EXPECT_EQ(s.patches[g.face(0, 0)].size(), 9);   // a surface corner
}

TEST(SmoothSurface, FlatUniformGridIsReproducedExactly) {
  const Grid g = Grid::flat(4, 3, 0.25);
  const SmoothSurface s = smooth_surface(g.faces);
  ASSERT_TRUE(s.ok());
  for (int f = 0; f < static_cast<int>(g.faces.size()); ++f)
    for (const Eigen::Vector2d xi :
         {Eigen::Vector2d(-1, -1), Eigen::Vector2d(0.3, -0.7), Eigen::Vector2d(1, 1)}) {
      const TensorPatch bilinear = bilinear_patch(g.faces[f]);
      EXPECT_LT((point(s.patches[f], g.x, xi) - point(bilinear, g.x, xi)).norm(), 1e-14) << "face " << f;
    }
}

/// Value, both tangents and the cross derivative agree where face f meets its ξ¹-neighbour.
void expect_c1_across(const Grid& g, const SmoothSurface& s, int f, int right, double v) {
  const PatchFrame a = patch_frame(s.patches[f], g.x, {1, v});
  const PatchFrame b = patch_frame(s.patches[right], g.x, {-1, v});
  EXPECT_LT((a.y - b.y).norm(), 1e-13);
  EXPECT_LT((a.tau1 - b.tau1).norm(), 1e-12);
  EXPECT_LT((a.tau2 - b.tau2).norm(), 1e-12);
  EXPECT_LT((a.normal - b.normal).norm(), 1e-12);
}

TEST(SmoothSurface, IsC1AcrossInteriorAndRimEdges) {
  const Grid g = Grid::curved(5, 4);
  const SmoothSurface s = smooth_surface(g.faces);
  ASSERT_TRUE(s.ok());
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i + 1 < 4; ++i)
      for (double v : {-1.0, -0.4, 0.5, 1.0}) expect_c1_across(g, s, g.face(i, j), g.face(i + 1, j), v);
}

TEST(SmoothSurface, RimOfAPlateInterpolatesItsNodes) {
  const Grid g = Grid::curved(4, 4);
  const SmoothSurface s = smooth_surface(g.faces);
  ASSERT_TRUE(s.ok());
  // The surface corner node and a straight-rim node are interpolated only on a flat rim; here we
  // check the corner's limit lies within 1 % of a face of its node.
  const Eigen::Vector3d corner = point(s.patches[g.face(0, 0)], g.x, {-1, -1});
  EXPECT_LT((corner - g.node(0, 0)).norm(), 0.01 * g.spacing);
}

TEST(SmoothSurface, RefusesExtraordinaryVertexAndNonManifoldEdge) {
  // The six faces of one hexahedron: every node lies in 3 faces (a cube corner), four per face.
  const std::vector<mesh::Quad> cube = mesh::boundary_faces({mesh::Hex{0, 1, 2, 3, 4, 5, 6, 7}});
  SmoothSurface s = smooth_surface(cube);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.problem.find("has extraordinary vertices at nodes"), std::string::npos) << s.problem;
  EXPECT_TRUE(s.patches.empty());
  const std::vector<mesh::Quad> fin = {{0, 1, 2, 3}, {1, 0, 4, 5}, {0, 1, 6, 7}};
  s = smooth_surface(fin);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.problem.find("edge (0, 1) lies in 3 faces"), std::string::npos) << s.problem;
}

TEST(SmoothSurface, ProjectionFindsTheBruteForceClosestPoint) {
  const Grid g = Grid::curved(5, 5);
  const SmoothSurface s = smooth_surface(g.faces);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.9, 0.9), lift(-0.1, 0.2);
  for (int trial = 0; trial < 40; ++trial) {
    const int f = g.face(1 + trial % 2, 1 + (trial / 2) % 2);
    const PatchFrame on = patch_frame(s.patches[f], g.x, {u(rng), u(rng)});
    const Eigen::Vector3d slave = on.y + lift(rng) * g.spacing * on.normal;
    const Projection p = patch_projection(slave, s.patches[f], g.x);
    ASSERT_TRUE(p.converged);
    EXPECT_LT((p.xi - on.xi).norm(), 1e-9);
    // brute force over a fine parameter grid of the patch, refined once
    double best = 1e300;
    for (int a = 0; a <= 200; ++a)
      for (int b = 0; b <= 200; ++b)
        best = std::min(best, (slave - point(s.patches[f], g.x, {-1 + a / 100.0, -1 + b / 100.0})).norm());
    EXPECT_LE(std::abs(p.gap), best + 1e-12);
    EXPECT_LT(best - std::abs(p.gap), 2e-4);  // the sampling's own resolution (ξ step 0.01)
  }
}

}  // namespace
}  // namespace stoss::contact
