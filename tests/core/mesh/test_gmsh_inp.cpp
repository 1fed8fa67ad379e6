// Requirements for Gmsh's Abaqus export (issue 25 §4), on tests/data/meshes/gmsh_box.inp written by Debian's
// gmsh 4.8.4 from gmsh_box.geo (a 2 × 1 × 1 box of 2 × 2 × 2 hexahedra): the CPS4 quadrangles of its
// physical surfaces become faces of surfaces of the same name, other 2D/1D elements are skipped with one
// note, *NSET node sets reach the body, and a *SURFACE holding interior faces is refused with its count.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <fstream>
#include <sstream>

#include "core/mesh/mesh_file.hpp"

namespace stoss::mesh {
namespace {

const std::filesystem::path deck = std::filesystem::path(STOSS_SOURCE_DIR) / "tests/data/meshes/gmsh_box.inp";

std::string deck_text() {
  std::ifstream in(deck);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// z of a quad's outward normal (b − a) × (d − a), for quads of `body`.
double normal_z(const BodyMesh& body, const Quad& q) {
  return (body.nodes[q[1]] - body.nodes[q[0]]).cross(body.nodes[q[3]] - body.nodes[q[0]]).z();
}

TEST(GmshInp, PhysicalSurfacesOfCps4BecomeOutwardSurfacesOfTheHexahedra) {
  const ImportedMesh m = read_abaqus(deck);
  EXPECT_EQ(m.nodes.size(), 27u);
  EXPECT_EQ(m.hex8.size(), 8u);
  EXPECT_EQ(m.element_sets.count("block"), 1u);
  EXPECT_EQ(m.element_sets.count("bottom"), 0u) << "an ELSET of 2D elements is a surface, not a body";
  ASSERT_EQ(m.notes.size(), 1u);
  EXPECT_NE(m.notes[0].find("8 2D/1D elements (CPS4)"), std::string::npos) << m.notes[0];
  EXPECT_NE(m.notes[0].find("8 on the hexahedra's boundary"), std::string::npos) << m.notes[0];
  EXPECT_NE(m.notes[0].find("0 skipped"), std::string::npos) << m.notes[0];
  const Selection s = select_body(m, std::string("block"));
  for (const auto& [name, sign] : {std::pair<std::string, double>{"bottom", -1}, {"top", 1}}) {
    ASSERT_TRUE(s.body.surfaces.contains(name)) << name;
    const std::vector<Quad>& faces = s.body.surfaces.at(name);
    EXPECT_EQ(faces.size(), 4u) << name;
    for (const Quad& q : faces) {
      for (int n : q) EXPECT_DOUBLE_EQ(s.body.nodes[n].z(), sign > 0 ? 1.0 : 0.0) << name;
      EXPECT_GT(sign * normal_z(s.body, q), 0) << name << ": faces point out of the box";
    }
  }
}

TEST(GmshInp, NodeSetsReachTheBodyAndABoundaryEntryCanNameThem) {
  const Selection s = select_body(read_abaqus(deck), std::string("block"));
  ASSERT_TRUE(s.body.node_sets.contains("bottom"));
  EXPECT_EQ(s.body.node_sets.at("bottom").size(), 9u);
  for (int n : s.body.node_sets.at("bottom")) EXPECT_DOUBLE_EQ(s.body.nodes[n].z(), 0.0);
  Mesh mesh;
  mesh.add_body("other", BodyMesh{{{0, 0, 5}}, {}, {}, {}});
  mesh.add_body("box", s.body);
  // "box/block" is a node set only (all 27 nodes, numbered after the other body's one); "box/top" a
  // surface and a node set: the surface's nodes.
  const std::vector<int> block = mesh.named_nodes("box/block");
  ASSERT_EQ(block.size(), 27u);
  EXPECT_EQ(block.front(), 1);
  EXPECT_EQ(block.back(), 27);
  EXPECT_EQ(mesh.named_nodes("box/top"), mesh.surface_nodes("box/top"));
  EXPECT_EQ(mesh.named_nodes("box/top").size(), 9u);
  try {
    mesh.named_nodes("box/sides");
    ADD_FAILURE() << "no surface or node set 'sides'";
  } catch (const std::out_of_range& e) {
    EXPECT_NE(std::string(e.what()).find("no surface or node set 'sides'"), std::string::npos) << e.what();
  }
}

TEST(GmshInp, TwoDElementsOffTheBoundaryAndLinesAreSkippedWithOneNote) {
  // An interior quadrangle (the mid-plane z = 0.5 face between two hexahedra) and a line element.
  std::string text = deck_text();
  text +=
      "*ELEMENT, type=CPS4, ELSET=inside\n101, 21, 27, 24, 11\n*ELEMENT, type=T3D2, ELSET=edge\n102, 1, 2\n";
  const ImportedMesh m = parse_abaqus(text, "gmsh_box+.inp", {});
  ASSERT_EQ(m.notes.size(), 1u);
  EXPECT_NE(m.notes[0].find("10 2D/1D elements (CPS4, T3D2)"), std::string::npos) << m.notes[0];
  EXPECT_NE(m.notes[0].find("2 skipped"), std::string::npos) << m.notes[0];
  EXPECT_FALSE(m.surfaces.contains("inside"));
  EXPECT_FALSE(m.element_sets.contains("inside")) << "its only element is a skipped 2D one";
}

TEST(GmshInp, ASurfaceOverInteriorFacesIsRefusedWithTheirCount) {
  // S2 of every element: the upper layer's are on the boundary, the lower layer's inside the box.
  const ImportedMesh m =
      parse_abaqus(deck_text() + "*SURFACE, NAME=all_s2\nblock, S2\n", "gmsh_box+.inp", {});
  try {
    select_body(m, std::string("block"));
    ADD_FAILURE() << "a surface with interior faces is accepted";
  } catch (const MeshFileError& e) {
    EXPECT_NE(std::string(e.what()).find("surface 'all_s2' holds 4 interior faces of 8"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace stoss::mesh
