// At an extraordinary vertex (the cube corners of a hollow_sphere mesh, valence 3) the smooth master
// surface shall be the Catmull–Clark limit surface, evaluated exactly as rings of regular pieces
// (docs/smooth_master_surface.md §2.5): a partition of unity, continuous with its tangent plane across
// the face's edges and across the pieces inside the face, defined arbitrarily close to the vertex, and
// its CPP shall find the brute-force closest point there.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "core/contact/geometry/patch_projection.hpp"
#include "core/contact/geometry/smooth_surface.hpp"
#include "core/mesh/generators.hpp"

namespace stoss::contact {
namespace {

struct Sphere {
  mesh::BodyMesh body = mesh::hollow_sphere({0, 0, 0}, 1.0, 0.8, 4, 1);
  std::vector<mesh::Quad> faces = body.surfaces.at("outer");
  Eigen::VectorXd x;
  SmoothSurface surface;
  Sphere() {
    x.resize(3 * body.nodes.size());
    for (size_t I = 0; I < body.nodes.size(); ++I) x.segment<3>(3 * I) = body.nodes[I];
    surface = smooth_surface(faces);
  }
  /// A face with an extraordinary corner, and that corner's index.
  std::pair<int, int> extraordinary_face() const {
    for (size_t f = 0; f < faces.size(); ++f)
      if (surface.patches[f].pieces) return {static_cast<int>(f), surface.patches[f].pieces->corner};
    return {-1, -1};
  }
  /// ξ of the face at local (u, v) measured from its extraordinary corner k.
  static Eigen::Vector2d face_xi(int k, double u, double v) {
    return detail::corner_rotation(k).transpose() * Eigen::Vector2d(2 * u - 1, 2 * v - 1);
  }
};

TEST(ExtraordinaryPatch, SphereSurfaceQualifiesWithPiecewiseFacesAtTheCubeCorners) {
  const Sphere s;
  ASSERT_TRUE(s.surface.ok()) << s.surface.problem;
  int piecewise = 0;
  for (const TensorPatch& p : s.surface.patches) piecewise += p.pieces != nullptr;
  EXPECT_EQ(piecewise, 24) << "8 corners × 3 faces";
  const auto [f, k] = s.extraordinary_face();
  EXPECT_EQ(s.surface.patches[f].size(), 2 * 3 + 8) << "the 2N + 8 nodes of the face's 1-ring";
}

TEST(ExtraordinaryPatch, IsAPartitionOfUnityOnEveryRing) {
  const Sphere s;
  const auto [f, k] = s.extraordinary_face();
  const TensorPatch& p = s.surface.patches[f];
  for (double t : {0.9, 0.6, 0.3, 0.1, 1e-3, 1e-6}) {
    const Eigen::Vector2d xi = Sphere::face_xi(k, t, 0.7 * t);
    const BasisValues<double> b = patch_values(p, xi[0], xi[1]);
    double sum = 0, sum1 = 0;
    for (int K = 0; K < p.size(); ++K) sum += b.N[K], sum1 += std::abs(b.N1[K]);
    EXPECT_NEAR(sum, 1, 1e-13) << t;
    EXPECT_GT(sum1, 0) << t;
  }
}

TEST(ExtraordinaryPatch, MeetsItsNeighboursWithMatchingPointAndNormal) {
  const Sphere s;
  const auto [f, k] = s.extraordinary_face();
  const mesh::Quad& q = s.faces[f];
  // Every edge of the face: the neighbour's point at the same place, and the same normal.
  for (int e = 0; e < 4; ++e) {
    const int a = q[e], b = q[(e + 1) % 4];
    int g = -1;
    for (size_t h = 0; h < s.faces.size(); ++h) {
      const mesh::Quad& r = s.faces[h];
      if (static_cast<int>(h) != f && std::count(r.begin(), r.end(), a) && std::count(r.begin(), r.end(), b))
        g = static_cast<int>(h);
    }
    ASSERT_GE(g, 0);
    const Eigen::Vector2d corner[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (double t : {0.02, 0.3, 0.7}) {
      const Eigen::Vector2d xi_f = (1 - t) * corner[e] + t * corner[(e + 1) % 4];
      const PatchFrame on_f = patch_frame(s.surface.patches[f], s.x, xi_f);
      const Projection on_g = patch_projection(on_f.y, s.surface.patches[g], s.x);
      ASSERT_TRUE(on_g.converged);
      EXPECT_LT(std::abs(on_g.gap), 1e-12) << "edge " << e << " t " << t;
      EXPECT_LT(std::abs(on_g.xi.cwiseAbs().maxCoeff() - 1), 1e-9) << "on the shared edge";
      EXPECT_LT((on_f.normal - on_g.frame.normal).norm(), 1e-10) << "edge " << e << " t " << t;
    }
  }
}

TEST(ExtraordinaryPatch, IsContinuousWithItsTangentsAcrossPiecesInsideTheFace) {
  const Sphere s;
  const auto [f, k] = s.extraordinary_face();
  const TensorPatch& p = s.surface.patches[f];
  for (double edge : {0.5, 0.25, 0.125}) {  // ring boundaries max(u, v) = 2⁻ⁿ
    const double d = 1e-10;
    const PatchFrame in = patch_frame(p, s.x, Sphere::face_xi(k, edge - d, 0.3 * edge));
    const PatchFrame out = patch_frame(p, s.x, Sphere::face_xi(k, edge + d, 0.3 * edge));
    EXPECT_LT((in.y - out.y).norm(), 1e-9) << edge;
    EXPECT_LT((in.tau1 - out.tau1).norm(), 1e-7 * in.tau1.norm()) << edge;
    EXPECT_LT((in.tau2 - out.tau2).norm(), 1e-7 * in.tau2.norm()) << edge;
  }
}

TEST(ExtraordinaryPatch, NormalIsDefinedRightNextToTheVertexAndPointsOutward) {
  const Sphere s;
  const auto [f, k] = s.extraordinary_face();
  const PatchFrame near = patch_frame(s.surface.patches[f], s.x, Sphere::face_xi(k, 1e-7, 1e-7));
  ASSERT_GT(near.normal.norm(), 0.5);
  EXPECT_GT(near.normal.dot(near.y.normalized()), 0.999) << "outward on a sphere";
  EXPECT_NEAR(near.y.norm(), 1.0, 0.05) << "the limit surface lies near the node net";
}

TEST(ExtraordinaryPatch, ProjectionFindsTheBruteForceClosestPointNearTheVertex) {
  const Sphere s;
  const auto [f, k] = s.extraordinary_face();
  const TensorPatch& p = s.surface.patches[f];
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.01, 0.6), lift(-0.02, 0.05);
  for (int trial = 0; trial < 12; ++trial) {
    const PatchFrame on = patch_frame(p, s.x, Sphere::face_xi(k, u(rng), u(rng)));
    const Eigen::Vector3d slave = on.y + lift(rng) * on.normal;
    const Projection proj = patch_projection(slave, p, s.x);
    ASSERT_TRUE(proj.converged) << trial;
    EXPECT_LT((proj.xi - on.xi).norm(), 1e-8) << trial;
    double best = 1e300;
    for (int a = 0; a <= 120; ++a)
      for (int b = 0; b <= 120; ++b)
        best = std::min(best, (slave - patch_frame(p, s.x, {-1 + a / 60.0, -1 + b / 60.0}).y).norm());
    EXPECT_LE(std::abs(proj.gap), best + 1e-12);
  }
}

}  // namespace
}  // namespace stoss::contact
