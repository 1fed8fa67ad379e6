// The massless contact surfaces of impact "located" (docs/theory.md §4.6.1, (4.13)): M' = Pᵀ M P has zero
// rows and columns at the slave and master nodes, is symmetric, keeps the total mass and hands each surface
// node's mass to the node behind it; other schemes and modes keep M; a surface node with nowhere to send its
// mass is an error; v ← P v gives a massless node its donor's velocity.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/contact/contact_mass.hpp"
#include "core/mesh/generators.hpp"

namespace stoss::contact {
namespace {

/// Two 2 × 2 × 2 boxes, b above a; a's top is the slave and b's bottom the master surface of a located pair;
/// a diagonal mass of 1 per node.
struct Box {
  model::Model m;
  solve::SparseMatrix M;
  Box() {
    m.mesh.add_body("a", mesh::box({0, 0, 0}, {1, 1, 1}, {2, 2, 2}));
    m.mesh.add_body("b", mesh::box({0, 0, 1.5}, {1, 1, 2.5}, {2, 2, 2}));
    model::ContactPair pair;
    pair.slave = "a/top";
    pair.master = "b/bottom";
    pair.impact = model::ImpactMode::located;
    m.contact.push_back(pair);
    m.time.scheme = model::Scheme::energy_momentum;
    M.resize(m.dof_count(), m.dof_count());
    M.setIdentity();
  }
};

/// The node at x, or −1.
int node_at(const mesh::Mesh& mesh, const Eigen::Vector3d& x) {
  for (int j = 0; j < mesh.node_count(); ++j)
    if ((mesh.nodes[j] - x).norm() < 1e-12) return j;
  return -1;
}

TEST(ContactMass, SurfaceNodesLoseTheirMassToTheNodesBehindAndTheTotalStays) {
  Box b;
  const solve::SparseMatrix Mp = contact_mass(b.m, b.M);
  const Eigen::MatrixXd dense(Mp);
  EXPECT_NEAR((dense - dense.transpose()).cwiseAbs().maxCoeff(), 0, 1e-15);
  EXPECT_NEAR(dense.sum(), Eigen::MatrixXd(b.M).sum(), 1e-12) << "total mass kept";
  std::vector<int> surfaces = b.m.mesh.surface_nodes("a/top");
  const std::vector<int> master = b.m.mesh.surface_nodes("b/bottom");
  ASSERT_EQ(surfaces.size(), 9u);
  ASSERT_EQ(master.size(), 9u);
  surfaces.insert(surfaces.end(), master.begin(), master.end());
  std::sort(surfaces.begin(), surfaces.end());
  EXPECT_EQ(massless_nodes(b.m), surfaces);
  for (int s : surfaces) {
    EXPECT_EQ(dense.row(3 * s).cwiseAbs().sum(), 0) << "node " << s;
    EXPECT_EQ(dense.col(3 * s + 2).cwiseAbs().sum(), 0) << "node " << s;
    // The node behind it (0.5 into its body) gets the surface node's unit mass on top of its own.
    const double inwards = b.m.mesh.nodes[s].z() < 1.25 ? -0.5 : 0.5;
    const int behind = node_at(b.m.mesh, b.m.mesh.nodes[s] + Eigen::Vector3d(0, 0, inwards));
    ASSERT_GE(behind, 0);
    EXPECT_NEAR(dense(3 * behind, 3 * behind), 2.0, 1e-15) << "node " << behind;
  }
}

TEST(ContactMass, TheVelocityMapGivesAMasslessNodeItsDonorsVelocityAndKeepsTheOthers) {
  Box b;
  const solve::SparseMatrix P = massless_velocity_map(b.m);
  ASSERT_EQ(P.rows(), b.m.dof_count());
  Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(b.m.dof_count(), 1, 2);
  const Eigen::VectorXd mapped = P * v;
  const std::vector<int> massless = massless_nodes(b.m);
  for (int I = 0; I < b.m.mesh.node_count(); ++I) {
    if (std::binary_search(massless.begin(), massless.end(), I)) continue;
    EXPECT_EQ((mapped.segment<3>(3 * I) - v.segment<3>(3 * I)).norm(), 0)
        << "node " << I << " keeps its v exactly";
  }
  const int s = b.m.mesh.surface_nodes("a/top").front();
  const int donor = node_at(b.m.mesh, b.m.mesh.nodes[s] - Eigen::Vector3d(0, 0, 0.5));
  EXPECT_EQ((mapped.segment<3>(3 * s) - v.segment<3>(3 * donor)).norm(), 0);
  b.m.contact[0].impact = model::ImpactMode::persist;
  EXPECT_EQ(massless_velocity_map(b.m).size(), 0) << "no massless node: no map";
}

TEST(ContactMass, OtherSchemesAndModesKeepTheMass) {
  Box b;
  b.m.time.scheme = model::Scheme::hht;  // needs M regular for a_0
  EXPECT_TRUE(massless_nodes(b.m).empty());
  EXPECT_EQ((Eigen::MatrixXd(contact_mass(b.m, b.M)) - Eigen::MatrixXd(b.M)).cwiseAbs().maxCoeff(), 0);
  b.m.time.scheme = model::Scheme::midpoint;
  EXPECT_EQ(massless_nodes(b.m).size(), 18u);
  b.m.contact[0].impact = model::ImpactMode::persist;
  EXPECT_TRUE(massless_nodes(b.m).empty());
}

TEST(ContactMass, ASurfaceNodeWithNoNodeOffTheContactSurfacesIsAnError) {
  model::Model m;
  m.mesh.add_body("a",
                  mesh::box({0, 0, 0}, {1, 1, 1}, {1, 1, 1}));  // one element: every node on top or bottom
  for (const char* surface : {"a/top", "a/bottom"}) {
    model::ContactPair pair;
    pair.slave = surface;
    pair.master = surface;
    pair.impact = model::ImpactMode::located;
    m.contact.push_back(pair);
  }
  solve::SparseMatrix M(m.dof_count(), m.dof_count());
  M.setIdentity();
  try {
    contact_mass(m, M);
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("nowhere to go"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("persist"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stoss::contact
