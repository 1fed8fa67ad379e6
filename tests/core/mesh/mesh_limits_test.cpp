// Requirements of issue 20 for the mesh readers: an uploaded deck reads no other file (*INCLUDE refused); a
// deck on disk includes only files below its own folder (no absolute path, no "..", no symbolic link leading
// out, depth and count capped); every count that drives memory is capped on its total, the caps follow
// max_nodes and the messages name the limit; no message echoes a line of a file other than the deck.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>

#include "core/mesh/mesh_file.hpp"

namespace stoss::mesh {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("stoss_mesh_limits_" + std::to_string(::getpid()) + "_" +
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

const std::string cube_nodes =
    "*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n";
const std::string cube = cube_nodes + "*ELEMENT, TYPE=C3D8, ELSET=EALL\n1,1,2,3,4,5,6,7,8\n";

template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const MeshFileError& e) {
    return e.what();
  }
  return "";
}

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
