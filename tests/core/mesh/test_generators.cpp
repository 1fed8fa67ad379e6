// Requirements for the mesh generators (docs/theory.md §1.1, §7).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "core/fem/hex8.hpp"
#include "core/mesh/generators.hpp"

namespace stoss::mesh {
namespace {

using Eigen::Vector3d;

std::array<double, 8> det_j0(const BodyMesh& m, const Hex& h) {
  fem::Matrix83 X;
  for (int I = 0; I < 8; ++I) X.row(I) = m.nodes[h[I]].transpose();
  return fem::jacobian_determinants(X);
}

double min_det_j0(const BodyMesh& m) {
  double lowest = INFINITY;
  for (const Hex& h : m.hex8)
    for (double d : det_j0(m, h)) lowest = std::min(lowest, d);
  return lowest;
}

/// Σ_e Σ_g w_g det J0 (weights 1): the discrete volume, = Σ_IJ M_IJ for ρ = 1 (docs/theory.md (1.9)).
double volume(const BodyMesh& m) {
  double v = 0;
  for (const Hex& h : m.hex8)
    for (double d : det_j0(m, h)) v += d;
  return v;
}

/// (b−a)×(d−a), the outward direction of a quad in outward order.
Vector3d quad_normal(const BodyMesh& m, const Quad& q) {
  return (m.nodes[q[1]] - m.nodes[q[0]]).cross(m.nodes[q[3]] - m.nodes[q[0]]);
}

Vector3d quad_centroid(const BodyMesh& m, const Quad& q) {
  return (m.nodes[q[0]] + m.nodes[q[1]] + m.nodes[q[2]] + m.nodes[q[3]]) / 4;
}

/// Area of the bilinear quad, 2×2 Gauss on |x_ξ × x_η|.
double quad_area(const BodyMesh& m, const Quad& q) {
  const double g = 1 / std::sqrt(3.0);
  double area = 0;
  for (double s : {-g, g})
    for (double t : {-g, g}) {
      const Vector3d dxds =
          ((1 - t) * (m.nodes[q[1]] - m.nodes[q[0]]) + (1 + t) * (m.nodes[q[2]] - m.nodes[q[3]])) / 4;
      const Vector3d dxdt =
          ((1 - s) * (m.nodes[q[3]] - m.nodes[q[0]]) + (1 + s) * (m.nodes[q[2]] - m.nodes[q[1]])) / 4;
      area += dxds.cross(dxdt).norm();
    }
  return area;
}

double surface_area(const BodyMesh& m, const std::string& name) {
  double a = 0;
  for (const Quad& q : m.surfaces.at(name)) a += quad_area(m, q);
  return a;
}

std::set<int> surface_nodes(const BodyMesh& m, const std::string& name) {
  std::set<int> out;
  for (const Quad& q : m.surfaces.at(name)) out.insert(q.begin(), q.end());
  return out;
}

std::multiset<Quad> as_set(const std::vector<Quad>& quads) {
  return {quads.begin(), quads.end()};
}

// ---------------------------------------------------------------------------------------------- box

TEST(Box, GivesTheStructuredGridCounts) {
  // The box generator shall give (nx+1)(ny+1)(nz+1) nodes, nx·ny·nz hex8 and one face per boundary cell.
  const BodyMesh m = box(Vector3d(0, 0, 0), Vector3d(1, 2, 3), {2, 3, 4});
  EXPECT_EQ(m.nodes.size(), 3u * 4u * 5u);
  EXPECT_EQ(m.hex8.size(), 24u);
  EXPECT_EQ(m.surfaces.size(), 6u);
  EXPECT_EQ(m.surfaces.at("xmin").size(), 12u);
  EXPECT_EQ(m.surfaces.at("xmax").size(), 12u);
  EXPECT_EQ(m.surfaces.at("ymin").size(), 8u);
  EXPECT_EQ(m.surfaces.at("ymax").size(), 8u);
  EXPECT_EQ(m.surfaces.at("bottom").size(), 6u);
  EXPECT_EQ(m.surfaces.at("top").size(), 6u);
}

TEST(Box, HasPositiveJacobianAndItsVolume) {
  // det J0 > 0 at every Gauss point, and Σ det J0 equals the box volume to 1e-12.
  const BodyMesh m = box(Vector3d(-1, -2, 0.5), Vector3d(3, 0, 1.7), {5, 3, 2});
  EXPECT_GT(min_det_j0(m), 0);
  EXPECT_NEAR(volume(m), 4 * 2 * 1.2, 1e-12);
}

TEST(Box, SurfaceNormalsPointOutwardsAndFacesLieOnTheirPlane) {
  const Vector3d lo(-1, -2, 0.5), hi(3, 0, 1.7);
  const BodyMesh m = box(lo, hi, {4, 3, 2});
  struct Plane {
    int axis;
    double side, level;
  };
  const std::map<std::string, Plane> planes{{"xmin", {0, -1, lo.x()}},   {"xmax", {0, 1, hi.x()}},
                                            {"ymin", {1, -1, lo.y()}},   {"ymax", {1, 1, hi.y()}},
                                            {"bottom", {2, -1, lo.z()}}, {"top", {2, 1, hi.z()}}};
  for (const auto& [name, plane] : planes) {
    const Vector3d outward = plane.side * Vector3d::Unit(plane.axis);
    for (const Quad& q : m.surfaces.at(name)) {
      EXPECT_NEAR((quad_normal(m, q).normalized() - outward).norm(), 0, 1e-12) << name;
      for (int n : q) EXPECT_DOUBLE_EQ(m.nodes[n][plane.axis], plane.level) << name;
    }
  }
}

TEST(Box, SurfacesTogetherAreTheBoundary) {
  // Every boundary face is in exactly one named surface, in the same (outward) order.
  const BodyMesh m = box(Vector3d(0, 0, 0), Vector3d(1, 1, 1), {3, 2, 4});
  std::vector<Quad> named;
  for (const auto& [name, quads] : m.surfaces) named.insert(named.end(), quads.begin(), quads.end());
  EXPECT_EQ(as_set(named), as_set(boundary_faces(m.hex8)));
}

TEST(Box, SingleElementFollowsTheReferenceNodeOrder) {
  // Local node I sits at corner (ξ_I, η_I, ζ_I) of docs/theory.md §1.1.
  const BodyMesh m = box(Vector3d(0, 0, 0), Vector3d(1, 1, 1), {1, 1, 1});
  const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                            {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  ASSERT_EQ(m.hex8.size(), 1u);
  for (int I = 0; I < 8; ++I)
    EXPECT_EQ(m.nodes[m.hex8[0][I]], Vector3d(corner[I][0], corner[I][1], corner[I][2])) << I;
}

TEST(Box, RejectsEmptyOrInvertedBoxes) {
  EXPECT_THROW(box(Vector3d(0, 0, 0), Vector3d(1, 0, 1), {1, 1, 1}), std::invalid_argument);
  EXPECT_THROW(box(Vector3d(0, 0, 0), Vector3d(1, 1, 1), {1, 0, 1}), std::invalid_argument);
}

// ------------------------------------------------------------------------------------ hollow sphere

const Vector3d seed_center(0, 0, 1.3);

BodyMesh seed_ball() {
  return hollow_sphere(seed_center, 1.0, 0.8, 6, 2);
}

TEST(HollowSphere, SeedBallHasThePublishedCounts) {
  // docs/theory.md §7: 654 nodes, 432 hex8, 218 slave nodes on the outer surface.
  const BodyMesh m = seed_ball();
  EXPECT_EQ(m.nodes.size(), 654u);
  EXPECT_EQ(m.hex8.size(), 432u);
  EXPECT_EQ(m.surfaces.size(), 2u);
  EXPECT_EQ(m.surfaces.at("outer").size(), 216u);
  EXPECT_EQ(m.surfaces.at("inner").size(), 216u);
  EXPECT_EQ(surface_nodes(m, "outer").size(), 218u);
  EXPECT_EQ(surface_nodes(m, "inner").size(), 218u);
}

TEST(HollowSphere, SeedBallHasPositiveJacobianAndTheReferenceVolume) {
  // §7 reference: min det J0 = 4.0e-4 and discrete mass m_b = 1.98376 for ρ = 1.
  const BodyMesh m = seed_ball();
  const double lowest = min_det_j0(m);
  EXPECT_GT(lowest, 0);
  EXPECT_NEAR(lowest, 4.0e-4, 0.05e-4);
  EXPECT_NEAR(volume(m), 1.98376, 1e-5);
}

TEST(HollowSphere, NodesLieOnTheirLayerRadius) {
  const BodyMesh m = seed_ball();
  for (const Vector3d& x : m.nodes) {
    const double r = (x - seed_center).norm();
    const double k = (r - 0.8) / 0.1;
    EXPECT_NEAR(k, std::round(k), 1e-9);
  }
  for (int n : surface_nodes(m, "outer")) EXPECT_NEAR((m.nodes[n] - seed_center).norm(), 1.0, 1e-12);
  for (int n : surface_nodes(m, "inner")) EXPECT_NEAR((m.nodes[n] - seed_center).norm(), 0.8, 1e-12);
}

TEST(HollowSphere, SharedNodesAreMergedAndAllNodesUsed) {
  const BodyMesh m = seed_ball();
  double closest = INFINITY;
  for (size_t a = 0; a < m.nodes.size(); ++a)
    for (size_t b = a + 1; b < m.nodes.size(); ++b)
      closest = std::min(closest, (m.nodes[a] - m.nodes[b]).norm());
  EXPECT_GT(closest, 1e-3);
  std::set<int> used;
  for (const Hex& h : m.hex8) used.insert(h.begin(), h.end());
  EXPECT_EQ(used.size(), m.nodes.size());
}

TEST(HollowSphere, SurfacesTogetherAreTheBoundary) {
  // Every boundary face of the shell is in `outer` or `inner`, in outward order.
  const BodyMesh m = seed_ball();
  std::vector<Quad> named = m.surfaces.at("outer");
  named.insert(named.end(), m.surfaces.at("inner").begin(), m.surfaces.at("inner").end());
  EXPECT_EQ(as_set(named), as_set(boundary_faces(m.hex8)));
}

struct Resolution {
  int divisions, layers;
};

class HollowSphereResolution : public ::testing::TestWithParam<Resolution> {};

TEST_P(HollowSphereResolution, CountsJacobianAndNormals) {
  // For any resolution: (6d²+2)(layers+1) nodes, 6d²·layers hex8, det J0 > 0, outer normals away
  // from the centre, inner normals towards it.
  const auto [d, layers] = GetParam();
  const Vector3d c(0.3, -0.2, 5);
  const BodyMesh m = hollow_sphere(c, 2.0, 0.5, d, layers);
  EXPECT_EQ(m.nodes.size(), static_cast<size_t>((6 * d * d + 2) * (layers + 1)));
  EXPECT_EQ(m.hex8.size(), static_cast<size_t>(6 * d * d * layers));
  EXPECT_GT(min_det_j0(m), 0);
  for (const Quad& q : m.surfaces.at("outer"))
    EXPECT_GT(quad_normal(m, q).normalized().dot((quad_centroid(m, q) - c).normalized()), 0.5);
  for (const Quad& q : m.surfaces.at("inner"))
    EXPECT_LT(quad_normal(m, q).normalized().dot((quad_centroid(m, q) - c).normalized()), -0.5);
}

INSTANTIATE_TEST_SUITE_P(Resolutions, HollowSphereResolution,
                         ::testing::Values(Resolution{1, 1}, Resolution{2, 1}, Resolution{3, 3},
                                           Resolution{5, 2}, Resolution{6, 2}, Resolution{9, 4}));

TEST(HollowSphere, SurfaceAreasApproachTheSphereAtSecondOrder) {
  // |A_d − 4πR²| / 4πR² falls by ≈ 4 per doubling of d and is below 1e-3 at d = 32.
  const double R = 1.5, r = 1.0;
  double previous_outer = 0, previous_inner = 0;
  for (int d : {4, 8, 16, 32}) {
    const BodyMesh m = hollow_sphere(Vector3d(1, 2, 3), R, r, d, 1);
    const double outer = std::abs(surface_area(m, "outer") / (4 * std::numbers::pi * R * R) - 1);
    const double inner = std::abs(surface_area(m, "inner") / (4 * std::numbers::pi * r * r) - 1);
    if (previous_outer > 0) {
      EXPECT_NEAR(previous_outer / outer, 4, 0.5) << d;
      EXPECT_NEAR(previous_inner / inner, 4, 0.5) << d;
    }
    previous_outer = outer;
    previous_inner = inner;
  }
  EXPECT_LT(previous_outer, 1e-3);
  EXPECT_LT(previous_inner, 1e-3);
}

TEST(HollowSphere, RejectsInvalidRadiiAndResolution) {
  EXPECT_THROW(hollow_sphere(Vector3d::Zero(), 0.8, 1.0, 6, 2), std::invalid_argument);
  EXPECT_THROW(hollow_sphere(Vector3d::Zero(), 1.0, 0.0, 6, 2), std::invalid_argument);
  EXPECT_THROW(hollow_sphere(Vector3d::Zero(), 1.0, 0.8, 0, 2), std::invalid_argument);
  EXPECT_THROW(hollow_sphere(Vector3d::Zero(), 1.0, 0.8, 6, 0), std::invalid_argument);
}

}  // namespace
}  // namespace stoss::mesh
