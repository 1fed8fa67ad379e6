// Which bodies of a static scene are held (docs/theory.md §5b.8): supports, and contacts with held bodies
// in the normal direction, must remove every rigid mode; what is left is named in the validator's rule.
#include <gtest/gtest.h>

#include "core/loads/held_bodies.hpp"
#include "core/mesh/generators.hpp"

namespace stoss::loads {
namespace {

/// Two stacked blocks: "lower" [0,1]² × [0,1] and "upper" [0,1]² × [1,2] (non-matching meshes).
struct TwoBlocks {
  mesh::Mesh mesh;
  std::vector<char> fixed;
  TwoBlocks() {
    mesh.add_body("lower", mesh::box({0, 0, 0}, {1, 1, 1}, {3, 3, 2}));
    mesh.add_body("upper", mesh::box({0, 0, 1}, {1, 1, 2}, {2, 2, 2}));
    fixed.assign(3 * mesh.node_count(), 0);
  }
  void hold(const std::string& surface, int direction) {
    for (int node : mesh.surface_nodes(surface)) fixed[3 * node + direction] = 1;
  }
  /// Every node on the line y = 0, z = 0 of a body held in every direction (a hinge along x).
  void hinge_along_x(int body) {
    for (int I = mesh.bodies[body].node_begin; I < mesh.bodies[body].node_end; ++I)
      if (mesh.nodes[I].y() == 0 && mesh.nodes[I].z() == 0)
        for (int k = 0; k < 3; ++k) fixed[3 * I + k] = 1;
  }
};

std::vector<std::string> described(const BodyFreedom& f) {
  std::vector<std::string> out;
  for (const RigidMode& m : f.free_modes) out.push_back(describe(m, f.centroid));
  return out;
}

TEST(HeldBodies, NothingHoldsAFreeBodyInAnyOfItsSixModes) {
  TwoBlocks b;
  const auto freedom = free_rigid_modes(b.mesh, b.fixed);
  ASSERT_EQ(freedom.size(), 2u);
  EXPECT_EQ(described(freedom[1]),
            (std::vector<std::string>{"translation along x", "translation along y", "translation along z",
                                      "rotation about x through (0.5, 0.5, 1.5)",
                                      "rotation about y through (0.5, 0.5, 1.5)",
                                      "rotation about z through (0.5, 0.5, 1.5)"}));
}

TEST(HeldBodies, RollersHoldABlockAndOneRollerLeavesThreeModes) {
  TwoBlocks b;
  b.hold("lower/bottom", 2);
  EXPECT_EQ(described(free_rigid_modes(b.mesh, b.fixed)[0]),
            (std::vector<std::string>{"translation along x", "translation along y",
                                      "rotation about z through (0.5, 0.5, 0.5)"}));
  b.hold("lower/xmin", 0);
  b.hold("lower/ymin", 1);
  EXPECT_TRUE(free_rigid_modes(b.mesh, b.fixed)[0].held());
}

TEST(HeldBodies, AHingeLeavesTheRotationAboutItsLine) {
  TwoBlocks b;
  b.hinge_along_x(0);
  const auto freedom = free_rigid_modes(b.mesh, b.fixed);
  EXPECT_EQ(described(freedom[0]), std::vector<std::string>{"rotation about x through (0.5, 0, 0)"});
  const std::string rule = rigid_mode_rule(b.mesh, freedom[0]);
  EXPECT_NE(rule.find("body 'lower' is free to move as a rigid body (rotation about x through (0.5, 0, 0))"),
            std::string::npos)
      << rule;
  EXPECT_NE(rule.find("supports, prescribed motions or contacts with held bodies"), std::string::npos)
      << rule;
}

TEST(HeldBodies, AContactWithAHeldBodyHoldsOnlyAlongTheNormal) {
  TwoBlocks b;
  b.hold("lower/bottom", 2);
  b.hold("lower/xmin", 0);
  b.hold("lower/ymin", 1);
  const std::vector<ContactSurfaces> contact{{"upper/bottom", {"lower/top"}}};
  const auto resting = free_rigid_modes(b.mesh, b.fixed, contact);
  EXPECT_TRUE(resting[0].held());
  EXPECT_EQ(described(resting[1]), (std::vector<std::string>{"translation along x", "translation along y",
                                                             "rotation about z through (0.5, 0.5, 1.5)"}))
      << "the contact holds z and the tilts, not the sliding";
  // The patch test's supports: rollers xmin (x) and ymin (y) on the upper block too; the contact holds z.
  b.hold("upper/xmin", 0);
  b.hold("upper/ymin", 1);
  EXPECT_EQ(described(free_rigid_modes(b.mesh, b.fixed)[1]), std::vector<std::string>{"translation along z"});
  EXPECT_TRUE(free_rigid_modes(b.mesh, b.fixed, contact)[1].held());
}

TEST(HeldBodies, AContactBetweenTwoFreeBodiesHoldsNeither) {
  TwoBlocks b;
  const std::vector<ContactSurfaces> contact{{"upper/bottom", {"lower/top"}}};
  const auto freedom = free_rigid_modes(b.mesh, b.fixed, contact);
  EXPECT_EQ(freedom[0].free_modes.size(), 6u);
  EXPECT_EQ(freedom[1].free_modes.size(), 6u);
}

TEST(HeldBodies, TheMasterSideIsHeldThroughAHeldSlave) {
  TwoBlocks b;
  for (int k = 0; k < 3; ++k) b.hold("upper/top", k);
  b.hold("lower/xmin", 0);
  b.hold("lower/ymin", 1);
  EXPECT_EQ(described(free_rigid_modes(b.mesh, b.fixed)[0]), std::vector<std::string>{"translation along z"});
  EXPECT_TRUE(free_rigid_modes(b.mesh, b.fixed, {{"upper/bottom", {"lower/top"}}})[0].held());
}

TEST(HeldBodies, AnUnknownContactSurfaceIsNamed) {
  TwoBlocks b;
  try {
    free_rigid_modes(b.mesh, b.fixed, {{"upper/bottom", {"lower/roof"}}});
    FAIL() << "an unknown surface accepted";
  } catch (const std::out_of_range& e) {
    EXPECT_NE(std::string(e.what()).find("no surface 'roof'"), std::string::npos) << e.what();
  }
}

TEST(HeldBodies, ARotatedAxisIsNamedByItsDirection) {
  const RigidMode slide{{0.6, 0.8, 0}, {0, 0, 0}};
  EXPECT_EQ(describe(slide, {0, 0, 0}), "translation along (0.6, 0.8, 0)");
  const RigidMode screw{{0, 0, 2}, {0, 0, 1}};
  EXPECT_EQ(describe(screw, {1, 2, 3}),
            "rotation about z through (1, 2, 3) with translation 2 per radian along it");
}

}  // namespace
}  // namespace stoss::loads
