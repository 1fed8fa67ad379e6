// Requirements for the mesh file readers: Gmsh MSH 4.1 (ASCII and binary, files written by Debian's gmsh)
// and Abaqus/CalculiX decks; one body cut out by element set, with its named surfaces; bad files are
// MeshFileErrors naming the file and the line or element.
#include "core/mesh/mesh_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/fem/hex8.hpp"

namespace stoss::mesh {
namespace {

namespace fs = std::filesystem;

const fs::path data_dir = fs::path(STOSS_SOURCE_DIR) / "tests/data/meshes";

/// A fresh directory under the system temp dir, removed at the end of the test.
struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("stoss_mesh_test_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name, std::ios::binary) << text;
    return path / name;
  }
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

double min_det_j0(const std::vector<Eigen::Vector3d>& nodes, const Hex& h) {
  fem::Matrix83 X;
  for (int I = 0; I < 8; ++I) X.row(I) = nodes[h[I]].transpose();
  const auto d = fem::jacobian_determinants(X);
  return *std::min_element(d.begin(), d.end());
}

Eigen::Vector3d normal(const std::vector<Eigen::Vector3d>& x, const Quad& q) {
  return (x[q[1]] - x[q[0]]).cross(x[q[3]] - x[q[0]]);
}

Eigen::Vector3d centroid(const std::vector<Eigen::Vector3d>& x, const Quad& q) {
  return (x[q[0]] + x[q[1]] + x[q[2]] + x[q[3]]) / 4;
}

/// The message of the MeshFileError `f` throws ("" if it throws none).
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const MeshFileError& e) {
    return e.what();
  }
  return "";
}

// ----------------------------------------------------------------------------------------------- Gmsh

/// The fixture two_blocks.geo: blocks [0,1]³ ("left") and [1,2]×[0,1]² ("right"), 2 hexahedra per edge.
void expect_two_blocks(const ImportedMesh& m) {
  EXPECT_EQ(m.nodes.size(), 45u);  // 5 × 3 × 3, the shared face merged
  ASSERT_EQ(m.hex8.size(), 16u);
  ASSERT_EQ(m.element_sets.size(), 2u);
  EXPECT_EQ(m.element_sets.at("left").size(), 8u);
  EXPECT_EQ(m.element_sets.at("right").size(), 8u);
  const auto element_x = [&](int e) {
    double x = 0;
    for (int n : m.hex8[e]) x += m.nodes[n].x() / 8;
    return x;
  };
  for (int e : m.element_sets.at("left")) EXPECT_LT(element_x(e), 1.0);
  for (int e : m.element_sets.at("right")) EXPECT_GT(element_x(e), 1.0);
  for (const Hex& h : m.hex8) EXPECT_GT(min_det_j0(m.nodes, h), 0);
  EXPECT_EQ(m.surfaces.at("bottom").size(), 8u);
  EXPECT_EQ(m.surfaces.at("top").size(), 8u);
  EXPECT_EQ(m.surfaces.at("xmax").size(), 4u);
  // Faces are oriented outwards from their element, whatever the quadrangle's orientation in the file.
  const std::map<std::string, Eigen::Vector3d> outward{{"bottom", -Eigen::Vector3d::UnitZ()},
                                                       {"top", Eigen::Vector3d::UnitZ()},
                                                       {"xmax", Eigen::Vector3d::UnitX()}};
  for (const auto& [name, direction] : outward)
    for (const ElementFace& f : m.surfaces.at(name)) {
      const Quad q = hex_faces(m.hex8[f.element])[f.face];
      EXPECT_NEAR(normal(m.nodes, q).normalized().dot(direction), 1.0, 1e-12) << name;
    }
}

TEST(GmshReader, ReadsAsciiFileWrittenByGmsh) {
  // gmsh 4.8.4 wrote tests/data/meshes/two_blocks_ascii.msh from two_blocks.geo (generate.sh).
  const ImportedMesh m = read_gmsh(data_dir / "two_blocks_ascii.msh", "two_blocks_ascii.msh");
  expect_two_blocks(m);
  EXPECT_EQ(m.file, "two_blocks_ascii.msh");
  EXPECT_GT(m.element_lines.front(), 0);
}

TEST(GmshReader, BinaryFileGivesTheSameMeshAsAscii) {
  const ImportedMesh a = read_gmsh(data_dir / "two_blocks_ascii.msh");
  const ImportedMesh b = read_gmsh(data_dir / "two_blocks_binary.msh");
  expect_two_blocks(b);
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.node_ids, b.node_ids);
  EXPECT_EQ(a.hex8, b.hex8);
  EXPECT_EQ(a.element_ids, b.element_ids);
  EXPECT_EQ(a.element_sets, b.element_sets);
  ASSERT_EQ(a.surfaces.size(), b.surfaces.size());
  for (const auto& [name, faces] : a.surfaces) {
    ASSERT_EQ(faces.size(), b.surfaces.at(name).size()) << name;
    for (size_t i = 0; i < faces.size(); ++i) {
      EXPECT_EQ(faces[i].element, b.surfaces.at(name)[i].element);
      EXPECT_EQ(faces[i].face, b.surfaces.at(name)[i].face);
    }
  }
}

TEST(GmshReader, ReadsWhatTheInstalledGmshWritesNow) {
  // The committed fixtures came from gmsh 4.8.4; this regenerates them with the gmsh on this machine.
  if (std::system("gmsh --version > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "gmsh is not installed (deploy/packages.txt installs it); the committed fixtures are tested above";
  TempDir dir;
  for (const char* flags : {"", "-bin"}) {
    const fs::path out = dir.path / (std::string("fresh") + flags + ".msh");
    const std::string command = "gmsh -3 -format msh41 " + std::string(flags) + " '" +
                                (data_dir / "two_blocks.geo").string() + "' -o '" + out.string() + "' > /dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    expect_two_blocks(read_mesh_file(out));
  }
}

TEST(GmshReader, SelectedPhysicalVolumeIsABodyWithItsSurfaces) {
  const ImportedMesh m = read_gmsh(data_dir / "two_blocks_binary.msh");
  const Selection left = select_body(m, "left");
  EXPECT_EQ(left.body.nodes.size(), 27u);
  EXPECT_EQ(left.body.hex8.size(), 8u);
  EXPECT_EQ(left.body.surfaces.at("bottom").size(), 4u);
  EXPECT_EQ(left.body.surfaces.at("top").size(), 4u);
  EXPECT_FALSE(left.body.surfaces.contains("xmax"));
  EXPECT_EQ(left.empty_surfaces, std::vector<std::string>{"xmax"});
  EXPECT_EQ(left.body.surfaces.at("boundary").size(), 24u);
  for (const auto& x : left.body.nodes) EXPECT_LE(x.x(), 1.0);
  const Selection all = select_body(m, std::nullopt);
  EXPECT_EQ(all.body.hex8.size(), 16u);
  EXPECT_EQ(all.body.surfaces.at("boundary").size(), 40u);
  EXPECT_EQ(all.body.surfaces.at("xmax").size(), 4u);
  EXPECT_NE(error_of([&] { select_body(m, "middle"); }).find("has no element set 'middle' (it has left, right)"),
            std::string::npos);
}

TEST(GmshReader, TransformScalesRotatesThenTranslates) {
  const ImportedMesh m = read_gmsh(data_dir / "two_blocks_ascii.msh");
  Transform t;
  t.scale = Eigen::Vector3d::Constant(2);
  t.axis = Eigen::Vector3d::UnitZ();
  t.degrees = 90;
  t.translate = Eigen::Vector3d(10, 0, 0);
  const Selection s = select_body(m, std::nullopt, t);
  for (size_t n = 0; n < m.nodes.size(); ++n) {
    const Eigen::Vector3d& x = m.nodes[n];
    const Eigen::Vector3d expected(10 - 2 * x.y(), 2 * x.x(), 2 * x.z());
    EXPECT_LT((s.body.nodes[n] - expected).norm(), 1e-12);
  }
  for (const Hex& h : s.body.hex8) EXPECT_NEAR(min_det_j0(s.body.nodes, h), 0.125, 1e-9);  // (2 · 0.5 / 2)³
}

/// A small hand-written ASCII MSH 4.1 file: one hexahedron, one quadrangle on its bottom; `elements` replaces
/// the $Elements body.
std::string one_hex_msh(const std::string& elements, const std::string& nodes_extra = "") {
  std::string nodes =
      "1 8 1 8\n3 1 0 8\n1\n2\n3\n4\n5\n6\n7\n8\n"
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n";
  return "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
         "$PhysicalNames\n2\n2 7 \"base\"\n3 8 \"solid\"\n$EndPhysicalNames\n"
         "$Entities\n0 0 1 1\n1 0 0 0 1 1 0 1 7 0\n1 0 0 0 1 1 1 1 8 0\n$EndEntities\n"
         "$Nodes\n" + (nodes_extra.empty() ? nodes : nodes_extra) + "$EndNodes\n"
         "$Elements\n" + elements + "$EndElements\n";
}

const std::string good_elements = "2 2 1 2\n2 1 3 1\n10 1 4 3 2\n3 1 5 1\n20 1 2 3 4 5 6 7 8\n";

TEST(GmshReader, HandWrittenFileWithNamedGroups) {
  TempDir dir;
  const ImportedMesh m = read_gmsh(dir.write("one.msh", one_hex_msh(good_elements)), "one.msh");
  ASSERT_EQ(m.hex8.size(), 1u);
  EXPECT_EQ(m.element_ids, std::vector<long>{20});
  EXPECT_EQ(m.element_lines, std::vector<long>{39});
  EXPECT_EQ(m.element_sets.at("solid"), std::vector<int>{0});
  ASSERT_EQ(m.surfaces.at("base").size(), 1u);
  EXPECT_EQ(m.surfaces.at("base")[0].face, 0);  // ζ−
  EXPECT_EQ(m.where_element(0), "one.msh:39: element 20");
}

TEST(GmshReader, BadFilesNameFileAndLine) {
  TempDir dir;
  const auto error = [&](const std::string& text) {
    const fs::path p = dir.write("bad.msh", text);
    return error_of([&] { read_gmsh(p, "bad.msh"); });
  };
  // Only 4.1.
  EXPECT_EQ(error("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"),
            "bad.msh:2: MSH format version 2.2 is not supported; Stoss reads version 4.1 (gmsh -format msh41)");
  EXPECT_EQ(error("hello\n"), "bad.msh:1: not a Gmsh mesh file: it must start with $MeshFormat");
  // Tetrahedra.
  EXPECT_NE(error(one_hex_msh("1 1 1 1\n3 1 4 1\n20 1 2 3 5\n")).find("bad.msh:36: unsupported volume element type 4 (4-node tetrahedron)"),
            std::string::npos);
  // Triangles in a physical surface.
  EXPECT_NE(error(one_hex_msh("1 1 1 1\n2 1 2 1\n20 1 2 3\n")).find("unsupported surface element type 2 (3-node triangle) in physical surface 'base'"),
            std::string::npos);
  // Wrong node count on an element line.
  EXPECT_EQ(error(one_hex_msh("1 1 1 1\n3 1 5 1\n20 1 2 3 4 5 6 7\n")),
            "bad.msh:37: element 20 has 7 node tags, type 5 (8-node hexahedron) needs 8");
  // Duplicate element and node tags.
  EXPECT_EQ(error(one_hex_msh("1 2 1 2\n3 1 5 2\n20 1 2 3 4 5 6 7 8\n20 1 2 3 4 5 6 7 8\n")),
            "bad.msh:38: duplicate element tag 20");
  EXPECT_NE(error(one_hex_msh(good_elements, "1 2 1 1\n3 1 0 2\n1\n1\n0 0 0\n1 0 0\n")).find("duplicate node tag 1"),
            std::string::npos);
  // A node that does not exist.
  EXPECT_EQ(error(one_hex_msh("1 1 1 1\n3 1 5 1\n20 1 2 3 4 5 6 7 9\n")),
            "bad.msh:37: element 20 refers to node 9, which $Nodes does not define");
  // A quadrangle of a physical surface that is no face of a hexahedron.
  EXPECT_EQ(error(one_hex_msh("2 2 1 2\n2 1 3 1\n10 1 2 7 8\n3 1 5 1\n20 1 2 3 4 5 6 7 8\n")),
            "bad.msh:37: quadrangle 10 of physical surface 'base' is not a face of any hexahedron");
  // Counts that do not match the blocks.
  EXPECT_NE(error(one_hex_msh("1 2 1 1\n3 1 5 1\n20 1 2 3 4 5 6 7 8\n")).find("header says 2 elements, its blocks hold 1"),
            std::string::npos);
  // Missing file.
  EXPECT_EQ(error_of([] { read_gmsh("/nonexistent/x.msh", "x.msh"); }), "x.msh: cannot read the file");
}

TEST(GmshReader, TruncatedFilesAreErrorsAtEveryCut) {
  // Cut both fixtures at many places: each cut is a MeshFileError, never a crash or a silent success
  // (except cuts in the trailing newline).
  TempDir dir;
  for (const char* name : {"two_blocks_ascii.msh", "two_blocks_binary.msh"}) {
    const std::string text = slurp(data_dir / name);
    int errors = 0, cuts = 0;
    for (size_t cut = 0; cut + 2 < text.size(); cut += 37) {
      const fs::path p = dir.write("cut.msh", text.substr(0, cut));
      ++cuts;
      const std::string message = error_of([&] { read_gmsh(p, "cut.msh"); });
      if (!message.empty()) ++errors;
      EXPECT_EQ(message.rfind("cut.msh", 0), 0u) << name << " cut at " << cut << ": " << message;
    }
    EXPECT_EQ(errors, cuts) << name;
  }
}

TEST(MeshFiles, MutatedFilesAreReadOrRefusedButNeverCrash) {
  // 400 deterministic single-byte mutations of each real fixture: every outcome is a mesh or a
  // MeshFileError (anything else — another exception, a crash, a hang — fails the test).
  TempDir dir;
  const std::vector<std::pair<fs::path, std::string>> fixtures{
      {data_dir / "two_blocks_ascii.msh", "m.msh"},
      {data_dir / "two_blocks_binary.msh", "m.msh"},
      {data_dir / "cgx_block.inp", "m.inp"},
      {fs::path(STOSS_SOURCE_DIR) / "api/examples/meshes/ball_plate.inp", "m.inp"}};
  const std::string replacements = "0 9-.,e\n$*x\xff\x00";
  unsigned state = 12345;
  const auto next = [&state] { return state = state * 1103515245u + 12345u, (state >> 8); };
  for (const auto& [fixture, name] : fixtures) {
    const std::string text = slurp(fixture);
    int refused = 0;
    for (int i = 0; i < 400; ++i) {
      std::string mutated = text;
      mutated[next() % mutated.size()] = replacements[next() % replacements.size()];
      const fs::path p = dir.write(name, mutated);
      try {
        const ImportedMesh m = read_mesh_file(p);
        select_body(m, std::nullopt);
      } catch (const MeshFileError&) {
        ++refused;
      }
    }
    EXPECT_GT(refused, 0) << fixture;
  }
}

// ------------------------------------------------------------------------------------------- Abaqus

/// Two stacked unit cubes (elements 1, 2) in set ELOW / EHIGH, surfaces on the bottom and the top.
const std::string two_cube_deck = R"(*HEADING
two cubes
** a comment
*NODE, NSET=NALL
1, 0, 0, 0
2, 1, 0, 0
3, 1, 1, 0
4, 0, 1, 0
5, 0, 0, 1
6, 1, 0, 1
7, 1, 1, 1
8, 0, 1, 1
9, 0., 0., 2.
10, 1.0, 0.0, 2.0
11, 1.0D0, 1., 2.
12, 0, 1, 2
*ELEMENT, TYPE=C3D8, ELSET=ELOW
1, 1, 2, 3, 4, 5, 6, 7, 8
*ELEMENT, TYPE=C3D8R, ELSET=EHIGH
2, 5, 6, 7, 8,
9, 10, 11, 12
*ELSET, ELSET=EALL
ELOW, EHIGH
*ELSET, ELSET=EGEN, GENERATE
1, 2, 1
*NSET, NSET=NBASE
1, 2, 3, 4
*SURFACE, NAME=SBOTTOM, TYPE=ELEMENT
ELOW, S1
*Surface, name=STop
2, S2
*SURFACE, NAME=SSIDES
EALL, S3
EALL, S4
EALL, S5
EALL, S6
*MATERIAL, NAME=STEEL
*ELASTIC
210000, 0.3
*STEP
*STATIC
*END STEP
)";

TEST(AbaqusReader, ReadsNodesElementsSetsAndSurfaces) {
  TempDir dir;
  const ImportedMesh m = read_abaqus(dir.write("cubes.inp", two_cube_deck), "cubes.inp");
  ASSERT_EQ(m.nodes.size(), 12u);
  EXPECT_EQ(m.nodes[10], Eigen::Vector3d(1, 1, 2));
  ASSERT_EQ(m.hex8.size(), 2u);
  EXPECT_EQ(m.element_lines, (std::vector<long>{18, 20}));
  EXPECT_EQ(m.element_sets.at("ELOW"), std::vector<int>{0});
  EXPECT_EQ(m.element_sets.at("EHIGH"), std::vector<int>{1});
  EXPECT_EQ(m.element_sets.at("EALL"), (std::vector<int>{0, 1}));
  EXPECT_EQ(m.element_sets.at("EGEN"), (std::vector<int>{0, 1}));
  for (const Hex& h : m.hex8) EXPECT_NEAR(min_det_j0(m.nodes, h), 0.125, 1e-12);
  ASSERT_EQ(m.surfaces.at("SBOTTOM").size(), 1u);
  ASSERT_EQ(m.surfaces.at("STop").size(), 1u);  // the name as written
  ASSERT_EQ(m.surfaces.at("SSIDES").size(), 8u);
  const auto outward = [&](const ElementFace& f) {
    const Quad q = hex_faces(m.hex8[f.element])[f.face];
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int n : m.hex8[f.element]) c += m.nodes[n] / 8;
    return normal(m.nodes, q).dot(centroid(m.nodes, q) - c) > 0;
  };
  EXPECT_NEAR(normal(m.nodes, hex_faces(m.hex8[0])[m.surfaces.at("SBOTTOM")[0].face]).normalized().z(), -1, 1e-12);
  EXPECT_NEAR(normal(m.nodes, hex_faces(m.hex8[1])[m.surfaces.at("STop")[0].face]).normalized().z(), 1, 1e-12);
  for (const ElementFace& f : m.surfaces.at("SSIDES")) {
    EXPECT_TRUE(outward(f));
    const Quad q = hex_faces(m.hex8[f.element])[f.face];
    EXPECT_NEAR(normal(m.nodes, q).z(), 0, 1e-12);  // S3..S6 are the side faces of a C3D8
  }
  // The faces S3..S6 of one element are four different sides: −y, +x, +y, −x.
  std::vector<Eigen::Vector3d> sides;
  for (const ElementFace& f : m.surfaces.at("SSIDES"))
    if (f.element == 0) sides.push_back(normal(m.nodes, hex_faces(m.hex8[0])[f.face]).normalized());
  ASSERT_EQ(sides.size(), 4u);
  EXPECT_LT((sides[0] - Eigen::Vector3d(0, -1, 0)).norm(), 1e-12);
  EXPECT_LT((sides[1] - Eigen::Vector3d(1, 0, 0)).norm(), 1e-12);
  EXPECT_LT((sides[2] - Eigen::Vector3d(0, 1, 0)).norm(), 1e-12);
  EXPECT_LT((sides[3] - Eigen::Vector3d(-1, 0, 0)).norm(), 1e-12);

  const Selection high = select_body(m, "EHIGH");
  EXPECT_EQ(high.body.nodes.size(), 8u);
  EXPECT_EQ(high.body.surfaces.at("STop").size(), 1u);
  EXPECT_EQ(high.body.surfaces.at("SSIDES").size(), 4u);
  EXPECT_EQ(high.empty_surfaces, std::vector<std::string>{"SBOTTOM"});
}

TEST(AbaqusReader, ReadsADeckWrittenByCalculixGraphix) {
  // cgx 2.17 wrote tests/data/meshes/cgx_block.inp (generate.sh): a 2 × 1 × 1 block, 4 × 2 × 2 C3D8.
  const ImportedMesh m = read_mesh_file(data_dir / "cgx_block.inp", "cgx_block.inp");
  EXPECT_EQ(m.nodes.size(), 45u);
  ASSERT_EQ(m.hex8.size(), 16u);
  EXPECT_EQ(m.element_sets.at("Eall").size(), 16u);
  double volume = 0;
  for (const Hex& h : m.hex8) {
    EXPECT_NEAR(min_det_j0(m.nodes, h), 0.125 * 0.125, 1e-12);  // cgx's C3D8 node order is Stoss's
    volume += 8 * min_det_j0(m.nodes, h);
  }
  EXPECT_NEAR(volume, 2.0, 1e-12);
  const Selection s = select_body(m, "EALL");  // Abaqus names ignore case
  EXPECT_EQ(s.body.surfaces.at("boundary").size(), 2u * (8 + 4 + 8));
}

TEST(AbaqusReader, IncludedFilesAreRead) {
  TempDir dir;
  dir.write("nodes.inp", "1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n");
  const ImportedMesh m = read_abaqus(
      dir.write("main.inp", "*NODE\n*INCLUDE, INPUT=nodes.inp\n*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7,8\n"), "main.inp");
  EXPECT_EQ(m.nodes.size(), 8u);
  EXPECT_EQ(m.hex8.size(), 1u);
}

TEST(AbaqusReader, BadDecksNameFileAndLine) {
  TempDir dir;
  const std::string nodes = "*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n";
  const auto error = [&](const std::string& text) {
    const fs::path p = dir.write("bad.inp", text);
    return error_of([&] { read_abaqus(p, "bad.inp"); });
  };
  EXPECT_EQ(error(nodes + "*ELEMENT, TYPE=C3D4\n1,1,2,3,5\n"),
            "bad.inp:10: unsupported element type C3D4; Stoss reads 8-node hexahedra (C3D8, C3D8R)");
  EXPECT_EQ(error(nodes + "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7\n"), "bad.inp:11: element 1 has 7 nodes, C3D8 needs 8");
  EXPECT_EQ(error(nodes + "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7,8,9\n"), "bad.inp:11: element 1 has 9 nodes, C3D8 needs 8");
  EXPECT_EQ(error(nodes + "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,\n"),
            "bad.inp:11: element line ends with ',' but the file ends (truncated file?)");
  EXPECT_EQ(error(nodes + "3,5,5,5\n"), "bad.inp:10: duplicate node id 3 (first defined on line 4)");
  EXPECT_EQ(error(nodes + "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7,8\n1,1,2,3,4,5,6,7,8\n"),
            "bad.inp:12: duplicate element id 1 (first defined on line 11)");
  EXPECT_EQ(error(nodes + "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7,99\n"),
            "bad.inp:11: element 1 refers to node 99, which no *NODE defines");
  EXPECT_EQ(error(nodes + "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7,8\n*SURFACE, NAME=S\nEBALL, S1\n"),
            "bad.inp:13: *SURFACE S: 'EBALL' is neither an element nor an ELSET");
  EXPECT_EQ(error(nodes + "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7,8\n*SURFACE, NAME=S\n1, S7\n"),
            "bad.inp:13: face label must be S1..S6 (C3D8 faces), got 'S7'");
  EXPECT_EQ(error(nodes + "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7,8\n*SURFACE, NAME=S\n2, S1\n"),
            "bad.inp:13: *SURFACE S: element 2 is not defined");
  EXPECT_EQ(error(nodes + "*SURFACE, NAME=S, TYPE=NODE\n1\n"),
            "bad.inp:10: *SURFACE TYPE=NODE is not supported; Stoss reads element-based surfaces (TYPE=ELEMENT)");
  EXPECT_EQ(error(nodes + "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7,8\n*ELSET, ELSET=E\n1, 5\n"),
            "bad.inp:13: ELSET E: element 5 is not defined");
  EXPECT_EQ(error("*NODE\n1, 0, zero, 0\n"), "bad.inp:2: expected y (a number), got 'zero'");
  EXPECT_EQ(error("1, 0, 0, 0\n"), "bad.inp:1: data line before any keyword");
  EXPECT_EQ(
      error(nodes + "*ELSET, ELSET=E, GENERATE\n1, 100000000\n"),
      "bad.inp:11: more than 80000000 set members in all sets and surfaces (8 × the limit of 10000000 nodes "
      "per mesh file)");
  EXPECT_EQ(error_of([] { read_mesh_file("part.stl"); }),
            "part.stl: unknown mesh file type '.stl' (Stoss reads Gmsh .msh 4.1 and Abaqus/CalculiX .inp)");
}

TEST(AbaqusReader, EmptyAndMissingSetsAreNamedWhenSelected) {
  TempDir dir;
  const ImportedMesh m = read_abaqus(
      dir.write("e.inp", "*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
                         "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7,8\n*ELSET, ELSET=EMPTY\n"),
      "e.inp");
  EXPECT_EQ(error_of([&] { select_body(m, "EMPTY"); }), "e.inp: element set 'EMPTY' is empty");
  EXPECT_EQ(error_of([&] { select_body(m, "EBALL"); }), "e.inp: has no element set 'EBALL' (it has EMPTY)");
}

}  // namespace
}  // namespace stoss::mesh
