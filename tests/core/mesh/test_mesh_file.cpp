// Requirements for the mesh file readers: Gmsh MSH 4.1 (ASCII and binary, files written by Debian's gmsh)
// and Abaqus/CalculiX decks; one body cut out by element set, with its named surfaces; bad files are
// MeshFileErrors naming the file and the line or element.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/fem/hex8.hpp"
#include "core/mesh/mesh_file.hpp"

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
    fs::create_directories((path / name).parent_path());
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
    GTEST_SKIP()
        << "gmsh is not installed (deploy/packages.txt installs it); the committed fixtures are tested above";
  TempDir dir;
  for (const char* flags : {"", "-bin"}) {
    const fs::path out = dir.path / (std::string("fresh") + flags + ".msh");
    const std::string command = "gmsh -3 -format msh41 " + std::string(flags) + " '" +
                                (data_dir / "two_blocks.geo").string() + "' -o '" + out.string() +
                                "' > /dev/null 2>&1";
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
  EXPECT_NE(
      error_of([&] { select_body(m, "middle"); }).find("has no element set 'middle' (it has left, right)"),
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
         "$Nodes\n" +
         (nodes_extra.empty() ? nodes : nodes_extra) +
         "$EndNodes\n"
         "$Elements\n" +
         elements + "$EndElements\n";
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
  EXPECT_EQ(
      error("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"),
      "bad.msh:2: MSH format version 2.2 is not supported; Stoss reads version 4.1 (gmsh -format msh41)");
  EXPECT_EQ(error("hello\n"), "bad.msh:1: not a Gmsh mesh file: it must start with $MeshFormat");
  // Tetrahedra.
  EXPECT_NE(error(one_hex_msh("1 1 1 1\n3 1 4 1\n20 1 2 3 5\n"))
                .find("bad.msh:36: unsupported volume element type 4 (4-node tetrahedron)"),
            std::string::npos);
  // Triangles in a physical surface.
  EXPECT_NE(error(one_hex_msh("1 1 1 1\n2 1 2 1\n20 1 2 3\n"))
                .find("unsupported surface element type 2 (3-node triangle) in physical surface 'base'"),
            std::string::npos);
  // Wrong node count on an element line.
  EXPECT_EQ(error(one_hex_msh("1 1 1 1\n3 1 5 1\n20 1 2 3 4 5 6 7\n")),
            "bad.msh:37: element 20 has 7 node tags, type 5 (8-node hexahedron) needs 8");
  // Duplicate element and node tags.
  EXPECT_EQ(error(one_hex_msh("1 2 1 2\n3 1 5 2\n20 1 2 3 4 5 6 7 8\n20 1 2 3 4 5 6 7 8\n")),
            "bad.msh:38: duplicate element tag 20");
  EXPECT_NE(error(one_hex_msh(good_elements, "1 2 1 1\n3 1 0 2\n1\n1\n0 0 0\n1 0 0\n"))
                .find("duplicate node tag 1"),
            std::string::npos);
  // A node that does not exist.
  EXPECT_EQ(error(one_hex_msh("1 1 1 1\n3 1 5 1\n20 1 2 3 4 5 6 7 9\n")),
            "bad.msh:37: element 20 refers to node 9, which $Nodes does not define");
  // A quadrangle of a physical surface that is no face of a hexahedron.
  EXPECT_EQ(error(one_hex_msh("2 2 1 2\n2 1 3 1\n10 1 2 7 8\n3 1 5 1\n20 1 2 3 4 5 6 7 8\n")),
            "bad.msh:37: quadrangle 10 of physical surface 'base' is not a face of any hexahedron");
  // Counts that do not match the blocks.
  EXPECT_NE(error(one_hex_msh("1 2 1 1\n3 1 5 1\n20 1 2 3 4 5 6 7 8\n"))
                .find("header says 2 elements, its blocks hold 1"),
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
  EXPECT_NEAR(normal(m.nodes, hex_faces(m.hex8[0])[m.surfaces.at("SBOTTOM")[0].face]).normalized().z(), -1,
              1e-12);
  EXPECT_NEAR(normal(m.nodes, hex_faces(m.hex8[1])[m.surfaces.at("STop")[0].face]).normalized().z(), 1,
              1e-12);
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
      dir.write("main.inp", "*NODE\n*INCLUDE, INPUT=nodes.inp\n*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7,8\n"),
      "main.inp");
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
  EXPECT_EQ(error(nodes + "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7\n"),
            "bad.inp:11: element 1 has 7 nodes, C3D8 needs 8");
  EXPECT_EQ(error(nodes + "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7,8,9\n"),
            "bad.inp:11: element 1 has 9 nodes, C3D8 needs 8");
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
  EXPECT_EQ(
      error(nodes + "*SURFACE, NAME=S, TYPE=NODE\n1\n"),
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
  const ImportedMesh m =
      read_abaqus(dir.write("e.inp",
                            "*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
                            "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7,8\n*ELSET, ELSET=EMPTY\n"),
                  "e.inp");
  EXPECT_EQ(error_of([&] { select_body(m, "EMPTY"); }), "e.inp: element set 'EMPTY' is empty");
  EXPECT_EQ(error_of([&] { select_body(m, "EBALL"); }), "e.inp: has no element set 'EBALL' (it has EMPTY)");
}

// ------------------------------------------------------------------------------------ limits (issue 20)

// Requirements of issue 20 for the mesh readers: an uploaded deck reads no other file (*INCLUDE refused); a
// deck on disk includes only files below its own folder (no absolute path, no "..", no symbolic link leading
// out, depth and count capped); every count that drives memory is capped on its total, the caps follow
// max_nodes and the messages name the limit; no message echoes a line of a file other than the deck.

const std::string cube_nodes =
    "*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n";
const std::string cube = cube_nodes + "*ELEMENT, TYPE=C3D8, ELSET=EALL\n1,1,2,3,4,5,6,7,8\n";

std::string upload_error(const std::string& deck, long long max_nodes = 200'000) {
  return error_of([&] { parse_abaqus(deck, "request body", upload_limits(max_nodes)); });
}

TEST(UploadedDeck, AnIncludeIsRefusedWhateverItNamesAndNothingOfTheFileIsEchoed) {
  for (const std::string target : {"/etc/passwd", "../jobs.db", "/proc/self/cmdline", "/dev/zero",
                                   "/dev/urandom", "nodes.inp", "\"/etc/passwd\""}) {
    SCOPED_TRACE(target);
    const std::string message = upload_error("*NODE\n*INCLUDE, INPUT=" + target + "\n" + cube);
    EXPECT_EQ(
        message.rfind(
            "request body:2: *INCLUDE is not accepted here: an uploaded mesh must be self-contained", 0),
        0u)
        << message;
    EXPECT_EQ(message.find("root:"), std::string::npos) << message;
  }
  // Inside a *SURFACE (where the first report came from) too.
  EXPECT_NE(
      upload_error(cube + "*SURFACE, NAME=S\n*INCLUDE, INPUT=/etc/passwd\n").find("*INCLUDE is not accepted"),
      std::string::npos);
}

TEST(DeckOnDisk, IncludesBelowTheDecksFolderAreRead) {
  TempDir dir;
  dir.write("parts/nodes.inp", cube_nodes.substr(6) /* without *NODE */);
  dir.write("parts/elements.inp", "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7,8\n");
  dir.write("parts/all.inp", "*NODE\n*INCLUDE, INPUT=nodes.inp\n*INCLUDE, INPUT=elements.inp\n");
  const ImportedMesh m = read_abaqus(dir.write("main.inp", "*INCLUDE, INPUT=parts/all.inp\n"), "main.inp");
  EXPECT_EQ(m.nodes.size(), 8u);
  EXPECT_EQ(m.hex8.size(), 1u);
}

TEST(DeckOnDisk, AbsolutePathsDotDotAndLinksLeadingOutAreRefused) {
  TempDir dir;
  dir.write("outside/secret.inp", "1,0,0,0\n");
  const fs::path deck_dir = dir.path / "deck";
  fs::create_directories(deck_dir / "sub");
  fs::create_symlink("/etc/passwd", deck_dir / "passwd.inp");
  fs::create_symlink("/dev/zero", deck_dir / "zero.inp");
  fs::create_symlink(dir.path / "outside", deck_dir / "out");
  std::ofstream(deck_dir / "sub" / "up.inp") << "*INCLUDE, INPUT=../secret.inp\n";
  const auto error = [&](const std::string& input) {
    std::ofstream(deck_dir / "main.inp") << "*NODE\n*INCLUDE, INPUT=" << input << "\n";
    return error_of([&] { read_abaqus(deck_dir / "main.inp", "main.inp"); });
  };
  EXPECT_EQ(error("/etc/passwd"),
            "main.inp:2: *INCLUDE of an absolute path (/etc/passwd) is refused: only files below the deck's "
            "folder");
  EXPECT_EQ(error("/proc/self/cmdline").find("absolute path"), 27u);
  EXPECT_EQ(error("/dev/urandom").find("absolute path"), 27u);
  EXPECT_EQ(error("../outside/secret.inp"),
            "main.inp:2: *INCLUDE of a path with '..' (../outside/secret.inp) is refused: only files below "
            "the deck's "
            "folder");
  EXPECT_EQ(error("passwd.inp"),
            "main.inp:2: *INCLUDE of passwd.inp leads outside the deck's folder (a symbolic link?): refused");
  EXPECT_EQ(error("zero.inp"),
            "main.inp:2: *INCLUDE of zero.inp leads outside the deck's folder (a symbolic link?): refused");
  EXPECT_EQ(error("out/secret.inp").find("leads outside the deck's folder"), 39u);
  EXPECT_EQ(error("sub/up.inp"),
            "sub/up.inp:1: *INCLUDE of a path with '..' (../secret.inp) is refused: only files below the "
            "deck's folder");
  EXPECT_EQ(error("missing.inp"), "main.inp:2: cannot read included file missing.inp");
  // A FIFO below the folder never ends: only regular files are read.
  ASSERT_EQ(::mkfifo((deck_dir / "fifo.inp").c_str(), 0600), 0);
  EXPECT_EQ(error("fifo.inp"), "main.inp:2: cannot read included file fifo.inp");
}

TEST(DeckOnDisk, IncludesAreCappedInDepthAndInNumber) {
  TempDir dir;
  EXPECT_EQ(error_of([&] { read_abaqus(dir.write("self.inp", "*INCLUDE, INPUT=self.inp\n"), "self.inp"); }),
            "self.inp:1: *INCLUDE nested more than 8 deep");
  std::string fan;
  for (int i = 0; i < 101; ++i) fan += "*INCLUDE, INPUT=empty.inp\n";
  dir.write("empty.inp", "** nothing\n");
  EXPECT_EQ(error_of([&] { read_abaqus(dir.write("fan.inp", fan), "fan.inp"); }),
            "fan.inp:101: more than 100 *INCLUDE in all");
  // A chain of includes each naming the next twice: 2^8 copies would be read without the count cap.
  for (int level = 0; level < 8; ++level)
    dir.write("chain" + std::to_string(level) + ".inp", "*INCLUDE, INPUT=chain" + std::to_string(level + 1) +
                                                            ".inp\n*INCLUDE, INPUT=chain" +
                                                            std::to_string(level + 1) + ".inp\n");
  dir.write("chain8.inp", "** leaf\n");
  EXPECT_NE(error_of([&] {
              read_abaqus(dir.path / "chain0.inp", "chain0.inp");
            }).find("more than 100 *INCLUDE in all"),
            std::string::npos);
}

TEST(UploadedDeck, GenerateRangesAreCappedOnTheTotalBeforeAnyIdIsStored) {
  // 2^63 - 1: the loop `id <= last` never ended, and id += step overflowed.
  EXPECT_EQ(upload_error(cube + "*NSET, NSET=N, GENERATE\n1, 9223372036854775807\n"),
            "request body:13: more than 1600000 set members in all sets and surfaces (8 × the server limit "
            "max_nodes "
            "= 200000)");
  EXPECT_EQ(upload_error(cube + "*NSET, NSET=N, GENERATE\n9223372036854775806, 9223372036854775807, "
                                "4611686018427387904\n"),
            "request body:13: NSET N: node 9223372036854775806 is not defined");
  // 100 lines of 10 million ids each: every line alone passed the old per-line cap.
  std::string lines;
  for (int i = 0; i < 100; ++i) lines += "1, 10000000\n";
  EXPECT_EQ(upload_error(cube + "*ELSET, ELSET=E, GENERATE\n" + lines)
                .find("request body:13: more than 1600000 set "
                      "members"),
            0u);
  // The cap follows max_nodes: 8 x 10.
  EXPECT_EQ(upload_error(cube + "*NSET, NSET=N, GENERATE\n1, 81\n", 10),
            "request body:13: more than 80 set members in all sets and surfaces (8 × the server limit "
            "max_nodes = 10)");
  EXPECT_EQ(upload_error(cube + "*NSET, NSET=N, GENERATE\n1, 8\n", 10), "");
}

TEST(UploadedDeck, ASetDoublingItselfIsCappedOnItsTotal) {
  std::string deck = cube + "*ELSET, ELSET=E\n1\n";
  for (int i = 0; i < 24; ++i) deck += "*ELSET, ELSET=E\nE, E\n";
  const std::string message = upload_error(deck);
  EXPECT_NE(message.find("more than 1600000 set members in all sets and surfaces"), std::string::npos)
      << message;
}

TEST(UploadedDeck, NodesElementsAndSurfaceFacesAreCapped) {
  std::string nodes = "*NODE\n";
  for (int i = 1; i <= 11; ++i) nodes += std::to_string(i) + ",0,0,0\n";
  EXPECT_EQ(upload_error(nodes, 10),
            "request body:12: the file has more than 10 nodes (the server limit max_nodes = 10)");
  std::string elements = cube + "*ELEMENT, TYPE=C3D8\n";
  for (int i = 2; i <= 11; ++i) elements += std::to_string(i) + ",1,2,3,4,5,6,7,8\n";
  EXPECT_EQ(upload_error(elements, 10),
            "request body:22: the file has more than 10 elements (the server limit max_nodes = 10)");
  // Each surface row naming an ELSET expands to all its elements: 100 rows of a 10-element set = 1000 faces.
  std::string big_set = cube_nodes + "*ELEMENT, TYPE=C3D8, ELSET=EALL\n";
  for (int i = 1; i <= 10; ++i) big_set += std::to_string(i) + ",1,2,3,4,5,6,7,8\n";
  big_set += "*SURFACE, NAME=S\n";
  for (int i = 0; i < 100; ++i) big_set += "EALL, S1\n";
  const std::string message = upload_error(big_set, 20);
  EXPECT_NE(message.find("more than 160 surface faces in all surfaces (8 × the server limit max_nodes = 20)"),
            std::string::npos)
      << message;
}

TEST(UploadedDeck, LongLinesAreRefusedBeforeTheyAreSplit) {
  EXPECT_EQ(upload_error(cube + "*NSET, NSET=N\n" + std::string(70'000, ',') + "\n"),
            "request body:13: line longer than 65536 bytes");
  EXPECT_EQ(upload_error("*NODE" + std::string(1000, '\n').replace(0, 1000, std::string(1000, ',')) + "\n" +
                         std::string(65'000, ',') + "\n" + std::string(1000, ',') + "\n1\n"),
            "request body:1: keyword line (with its continuation lines) longer than 65536 bytes");
}

// ----------------------------------------------------------------------------------------------- Gmsh

std::string gmsh_error(const std::string& text, long long max_nodes) {
  return error_of([&] { parse_gmsh(text, "request body", upload_limits(max_nodes)); });
}

TEST(UploadedGmshFile, CountsInHeadersAreCheckedBeforeTheBlocksAreRead) {
  const std::string format = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  EXPECT_EQ(gmsh_error(format + "$Nodes\n1 1000000000000 1 1000000000000\n", 1000),
            "request body:5: the file has more than 1000 nodes (the server limit max_nodes = 1000)");
  // A block that holds more than its header says is refused at the block.
  EXPECT_EQ(gmsh_error(format + "$Nodes\n1 2 1 2\n3 1 0 2000\n", 1000),
            "request body:6: the file has more than 1000 nodes (the server limit max_nodes = 1000)");
  EXPECT_EQ(gmsh_error(format + "$Entities\n0 0 0 1000000\n", 1000),
            "request body:5: the file has more than 4000 records (entities, physical groups, elements of "
            "every type) "
            "(4 × the server limit max_nodes = 1000)");
  EXPECT_EQ(gmsh_error(format + "$Nodes\n0 0 0 0\n$EndNodes\n$Elements\n1 5000 1 5000\n", 1000),
            "request body:8: the file has more than 4000 records (entities, physical groups, elements of "
            "every type) "
            "(4 × the server limit max_nodes = 1000)");
}

TEST(UploadedGmshFile, PhysicalTagsTimesQuadranglesAreCappedOnTheirTotal) {
  // One surface entity in 50 physical groups, 100 quadrangles on it: 5000 faces from a few kilobytes.
  std::string text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 1 1\n1 0 0 0 1 1 0 50";
  for (int p = 1; p <= 50; ++p) text += " " + std::to_string(p);
  text += " 0\n1 0 0 0 1 1 1 1 1 0\n$EndEntities\n$Nodes\n1 8 1 8\n3 1 0 8\n";
  for (int n = 1; n <= 8; ++n) text += std::to_string(n) + "\n";
  text += "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n$EndNodes\n$Elements\n2 101 1 101\n";
  text += "3 1 5 1\n1 1 2 3 4 5 6 7 8\n2 1 3 100\n";
  for (int q = 0; q < 100; ++q) text += std::to_string(q + 2) + " 1 2 3 4\n";
  text += "$EndElements\n";
  const std::string message = gmsh_error(text, 100);
  EXPECT_NE(message.find("more than 800 element set members and surface faces in all (8 × the server limit "
                         "max_nodes = 100)"),
            std::string::npos)
      << message;
  EXPECT_EQ(gmsh_error(text, 10'000), "");
}

}  // namespace
}  // namespace stoss::mesh
