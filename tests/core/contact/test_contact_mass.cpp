// The massless slave surface of impact "located" (docs/theory.md §4.6.1, (4.13)): M' = Pᵀ M P has zero rows
// and columns at the slave nodes, is symmetric, keeps the total mass and hands each slave node's mass to the
// node beneath it; other schemes and modes keep M; a slave node with nowhere to send its mass is an error.
#include <gtest/gtest.h>

#include "core/contact/contact_mass.hpp"
#include "core/mesh/generators.hpp"

namespace stoss::contact {
namespace {

/// A 2 × 2 × 2 box whose top is the slave surface of a located pair, and a diagonal mass of 1 per node.
struct Box {
  model::Model m;
  solve::SparseMatrix M;
  Box() {
    m.mesh.add_body("a", mesh::box({0, 0, 0}, {1, 1, 1}, {2, 2, 2}));
    model::ContactPair pair;
    pair.slave = "a/top";
    pair.master = "b/top";
    pair.impact = model::ImpactMode::located;
    m.contact.push_back(pair);
    m.time.scheme = model::Scheme::energy_momentum;
    M.resize(m.dof_count(), m.dof_count());
    M.setIdentity();
  }
};

TEST(ContactMass, SlaveNodesLoseTheirMassToTheNodesBeneathAndTheTotalStays) {
  Box b;
  const solve::SparseMatrix Mp = contact_mass(b.m, b.M);
  const Eigen::MatrixXd dense(Mp);
  EXPECT_NEAR((dense - dense.transpose()).cwiseAbs().maxCoeff(), 0, 1e-15);
  EXPECT_NEAR(dense.sum(), Eigen::MatrixXd(b.M).sum(), 1e-12) << "total mass kept";
  const std::vector<int> top = b.m.mesh.surface_nodes("a/top");
  ASSERT_EQ(top.size(), 9u);
  EXPECT_EQ(massless_nodes(b.m), top);
  for (int s : top) {
    EXPECT_EQ(dense.row(3 * s).cwiseAbs().sum(), 0) << "node " << s;
    EXPECT_EQ(dense.col(3 * s + 2).cwiseAbs().sum(), 0) << "node " << s;
    // The node beneath (z = 0.5) gets the slave node's unit mass on top of its own.
    int beneath = -1;
    for (int j = 0; j < b.m.mesh.node_count(); ++j)
      if ((b.m.mesh.nodes[j] - b.m.mesh.nodes[s] + Eigen::Vector3d(0, 0, 0.5)).norm() < 1e-12) beneath = j;
    ASSERT_GE(beneath, 0);
    EXPECT_NEAR(dense(3 * beneath, 3 * beneath), 2.0, 1e-15) << "node " << beneath;
  }
}

TEST(ContactMass, OtherSchemesAndModesKeepTheMass) {
  Box b;
  b.m.time.scheme = model::Scheme::hht;  // needs M regular for a_0
  EXPECT_TRUE(massless_nodes(b.m).empty());
  EXPECT_EQ((Eigen::MatrixXd(contact_mass(b.m, b.M)) - Eigen::MatrixXd(b.M)).cwiseAbs().maxCoeff(), 0);
  b.m.time.scheme = model::Scheme::midpoint;
  EXPECT_EQ(massless_nodes(b.m).size(), 9u);
  b.m.contact[0].impact = model::ImpactMode::persist;
  EXPECT_TRUE(massless_nodes(b.m).empty());
}

TEST(ContactMass, ASlaveNodeWithNoNodeOffTheSlaveSurfacesIsAnError) {
  model::Model m;
  m.mesh.add_body("a",
                  mesh::box({0, 0, 0}, {1, 1, 1}, {1, 1, 1}));  // one element: every node on top or bottom
  for (const char* surface : {"a/top", "a/bottom"}) {
    model::ContactPair pair;
    pair.slave = surface;
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
