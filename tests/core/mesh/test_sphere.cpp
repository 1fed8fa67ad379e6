// The solid `sphere` primitive (core/mesh/generators.hpp, docs/theory.md §5b.7): its volume converges to
// 4/3 π R³, every element has a positive Jacobian at its corners and Gauss points, and its `outer` surface is
// closed, consistently oriented outwards and is the whole boundary of the mesh.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include "core/fem/hex8.hpp"
#include "core/mesh/generators.hpp"

namespace stoss::mesh {
namespace {

const Eigen::Vector3d center(0.3, -1.0, 2.0);
constexpr double radius = 1.7;

fem::Matrix83 element_nodes(const BodyMesh& m, const Hex& h) {
  fem::Matrix83 X;
  for (int I = 0; I < 8; ++I) X.row(I) = m.nodes[h[I]].transpose();
  return X;
}

/// Σ_e Σ_g det J0 (weights 1): the mesh's volume.
double volume(const BodyMesh& m) {
  double v = 0;
  for (const Hex& h : m.hex8)
    for (double d : fem::jacobian_determinants(element_nodes(m, h))) v += d;
  return v;
}

/// The smallest det J over every element's corners and Gauss points, relative to the element's mean.
double min_relative_jacobian(const BodyMesh& m) {
  double lowest = INFINITY;
  for (const Hex& h : m.hex8) {
    const fem::Matrix83 X = element_nodes(m, h);
    const auto gauss = fem::jacobian_determinants(X);
    const double mean =
        (gauss[0] + gauss[1] + gauss[2] + gauss[3] + gauss[4] + gauss[5] + gauss[6] + gauss[7]) / 8;
    for (double d : gauss) lowest = std::min(lowest, d / mean);
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d xi(corner == 1 || corner == 2 || corner == 5 || corner == 6 ? 1 : -1,
                               corner == 2 || corner == 3 || corner == 6 || corner == 7 ? 1 : -1,
                               corner >= 4 ? 1 : -1);
      const Eigen::Matrix3d J = X.transpose() * fem::hex8_shape(xi).dN_dxi;
      lowest = std::min(lowest, J.determinant() / mean);
    }
  }
  return lowest;
}

struct Resolution {
  int divisions;
  double grading, radial_grading;
};

class SphereDivisions : public ::testing::TestWithParam<Resolution> {
 protected:
  BodyMesh mesh() const {
    return sphere(center, radius, GetParam().divisions,
                  {.grading = GetParam().grading, .radial_grading = GetParam().radial_grading});
  }
};

TEST_P(SphereDivisions, EveryJacobianIsPositive) {
  const BodyMesh m = mesh();
  EXPECT_GT(min_relative_jacobian(m), 0.3)
      << "det J at corners and Gauss points / element mean (lowest 0.35 at d = 2)";
}

TEST_P(SphereDivisions, OuterIsAClosedOutwardSurfaceOnTheSphere) {
  const BodyMesh m = mesh();
  ASSERT_EQ(m.surfaces.size(), 1u);
  const std::vector<Quad>& outer = m.surfaces.at("outer");
  const int d = GetParam().divisions;
  EXPECT_EQ(outer.size(), 6u * d * d);
  // Every directed edge once, and its reverse once: closed and consistently oriented.
  std::map<std::pair<int, int>, int> directed;
  std::set<int> nodes;
  for (const Quad& q : outer)
    for (int k = 0; k < 4; ++k) {
      ++directed[{q[k], q[(k + 1) % 4]}];
      nodes.insert(q[k]);
    }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second;
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u) << "edge " << edge.first << "-" << edge.second;
  }
  const long V = long(nodes.size()), E = long(directed.size()) / 2, F = long(outer.size());
  EXPECT_EQ(V - E + F, 2) << "Euler characteristic of a sphere";
  for (int n : nodes) EXPECT_NEAR((m.nodes[n] - center).norm(), radius, 1e-12 * radius);
  for (const Quad& q : outer) {
    const Eigen::Vector3d normal = (m.nodes[q[1]] - m.nodes[q[0]]).cross(m.nodes[q[3]] - m.nodes[q[0]]);
    EXPECT_GT(normal.dot(m.nodes[q[0]] - center), 0) << "outward order";
  }
  // outer is the mesh's whole boundary: no face inside was left unmatched by the node merge.
  std::multiset<std::set<int>> boundary, named;
  for (const Quad& q : boundary_faces(m.hex8)) boundary.insert({q.begin(), q.end()});
  for (const Quad& q : outer) named.insert({q.begin(), q.end()});
  EXPECT_EQ(boundary, named);
}

INSTANTIATE_TEST_SUITE_P(Sphere, SphereDivisions,
                         ::testing::Values(Resolution{1, 0, 0}, Resolution{2, 0, 0}, Resolution{3, 0, 0},
                                           Resolution{4, 0, 0}, Resolution{8, 0, 0}, Resolution{2, 3, 0},
                                           Resolution{4, 3, 0}, Resolution{8, 3, 0}, Resolution{8, 6, 0},
                                           Resolution{4, 0, 3}, Resolution{12, 4, 3}),
                         [](const auto& info) {
                           return "d" + std::to_string(info.param.divisions) + "_grading" +
                                  std::to_string(int(info.param.grading)) + "_radial" +
                                  std::to_string(int(info.param.radial_grading));
                         });

TEST(Sphere, VolumeConvergesToFourThirdsPiRCubed) {
  const double exact = 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
  double previous = INFINITY;
  for (int d : {2, 4, 8, 16}) {
    const double error = std::abs(volume(sphere(center, radius, d)) - exact) / exact;
    EXPECT_LT(error, 0.3 * previous) << "divisions " << d << ": second order, ×¼ per halving of the elements";
    previous = error;
  }
  EXPECT_LT(previous, 5e-3) << "divisions 16 (measured 4.2e-3)";
}

TEST(Sphere, ElementAndNodeCounts) {
  const int d = 4, layers = sphere_layers(d);
  const BodyMesh m = sphere(center, radius, d);
  EXPECT_EQ(m.hex8.size(), size_t(d * d * d + 6 * d * d * layers));
  // Core (d+1)³ nodes plus, per layer above the core, the (6 d² + 2) nodes of a cube-sphere grid.
  EXPECT_EQ(m.nodes.size(), size_t((d + 1) * (d + 1) * (d + 1) + layers * (6 * d * d + 2)));
}

/// The longest outer edge at the node nearest the pole c − R e_z.
double pole_edge(const BodyMesh& m) {
  int pole = 0;
  for (size_t n = 0; n < m.nodes.size(); ++n)
    if (m.nodes[n].z() < m.nodes[pole].z()) pole = int(n);
  double longest = 0;
  for (const Quad& q : m.surfaces.at("outer"))
    for (int k = 0; k < 4; ++k)
      if (q[k] == pole) longest = std::max(longest, (m.nodes[q[(k + 1) % 4]] - m.nodes[pole]).norm());
  return longest;
}

TEST(Sphere, GradingRefinesThePoles) {
  const int d = 8;
  const double kappa = 3;
  const double ratio = pole_edge(sphere(center, radius, d, {kappa})) / pole_edge(sphere(center, radius, d));
  // The angular step at the pole: π/4 · g(2/d) against π/4 · 2/d, g(s) = sinh(κ s)/sinh(κ) (5b.8).
  const double expected = std::sinh(kappa * 2 / d) / std::sinh(kappa) / (2.0 / d);
  EXPECT_NEAR(ratio, expected, 0.01 * expected) << "0.33 at d = 8, κ = 3";
}

TEST(Sphere, RadialGradingThinsTheOuterLayers) {
  const int d = 4, layers = sphere_layers(d);
  const double kappa = 2;
  const BodyMesh m = sphere(center, radius, d, {.radial_grading = kappa});
  // The cap's nodes on the ray from the centre towards −z: r_k = 0.4 R + 0.6 R s_k, s_k = 1 − sinh(κ(1 −
  // k/L))/sinh κ.
  std::vector<double> r;
  for (const Eigen::Vector3d& x : m.nodes) {
    const Eigen::Vector3d d_x = x - center;
    if (std::abs(d_x.x()) < 1e-9 && std::abs(d_x.y()) < 1e-9 && d_x.z() <= -0.4 * radius + 1e-9)
      r.push_back(-d_x.z());
  }
  std::sort(r.begin(), r.end());
  ASSERT_EQ(r.size(), size_t(layers + 1));
  for (int k = 0; k <= layers; ++k) {
    const double s = 1 - std::sinh(kappa * (1 - double(k) / layers)) / std::sinh(kappa);
    EXPECT_NEAR(r[k], (0.4 + 0.6 * s) * radius, 1e-12 * radius) << "layer " << k;
  }
  EXPECT_LT(r[layers] - r[layers - 1], 0.5 * (r[1] - r[0])) << "the outermost layer is the thinnest";
}

TEST(Sphere, AQuarterIsAQuarterOfTheSphereWithItsCutPlanesNamed) {
  for (double kappa : {0.0, 3.0}) {
    const BodyMesh full = sphere(center, radius, 6, {kappa});
    const BodyMesh quarter = sphere(center, radius, 6, {.grading = kappa, .quarter = true});
    EXPECT_EQ(quarter.hex8.size() * 4, full.hex8.size());
    EXPECT_NEAR(4 * volume(quarter), volume(full), 1e-12 * volume(full));
    EXPECT_GT(min_relative_jacobian(quarter), 0.3);
    ASSERT_EQ(quarter.surfaces.size(), 3u);
    const std::pair<const char*, Eigen::Vector3d> planes[] = {{"xmin", -Eigen::Vector3d::UnitX()},
                                                              {"ymin", -Eigen::Vector3d::UnitY()}};
    for (const auto& [name, outward] : planes)
      for (const Quad& q : quarter.surfaces.at(name)) {
        const Eigen::Vector3d n =
            (quarter.nodes[q[1]] - quarter.nodes[q[0]]).cross(quarter.nodes[q[3]] - quarter.nodes[q[0]]);
        EXPECT_GT(n.normalized().dot(outward), 1 - 1e-12) << name << ": flat, in outward order";
      }
    for (const Quad& q : quarter.surfaces.at("outer"))
      for (int n : q) EXPECT_NEAR((quarter.nodes[n] - center).norm(), radius, 1e-12 * radius);
    EXPECT_EQ(quarter.surfaces.at("outer").size() * 4, full.surfaces.at("outer").size());
    size_t named = 0;
    for (const auto& [name, faces] : quarter.surfaces) named += faces.size();
    EXPECT_EQ(named, boundary_faces(quarter.hex8).size()) << "the three surfaces are the whole boundary";
  }
}

TEST(Sphere, RefusesBadArguments) {
  EXPECT_THROW(sphere(center, 1, 5, {.quarter = true}), std::invalid_argument)
      << "a quarter of odd divisions";
  EXPECT_THROW(sphere(center, 1, 4, {.grading = -1}), std::invalid_argument);
  EXPECT_THROW(sphere(center, 1, 4, {.radial_grading = 11}), std::invalid_argument);
  EXPECT_THROW(sphere(center, 0, 4), std::invalid_argument);
  EXPECT_THROW(sphere(center, -1, 4), std::invalid_argument);
  EXPECT_THROW(sphere(center, 1, 0), std::invalid_argument);
}

}  // namespace
}  // namespace stoss::mesh
