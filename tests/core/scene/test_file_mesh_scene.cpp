// Requirements for scenes whose bodies come from mesh files: "mesh": {"file", "elements", "transform"}
// resolved relative to the scene file; the CalculiX-deck and Gmsh examples validate and run into
// contact; bad files are scene issues naming the file and the line or element.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/output/result_reader.hpp"
#include "core/output/result_writer.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"
#include "tests/core/recording_observer.hpp"

namespace stoss {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path examples = fs::path(STOSS_SOURCE_DIR) / "api/examples";

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("stoss_file_mesh_" + std::to_string(::getpid()) + "_" +
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

/// The issues of loading a scene file, one "pointer: message" per line ("" when it loads).
std::string issues_of(const fs::path& scene) {
  try {
    scene::load_file(scene.string());
  } catch (const scene::SceneError& e) {
    return e.what();
  }
  return "";
}

const json material = {{"youngs_modulus", 1e4}, {"poisson_ratio", 0.4}, {"density", 1}};

json one_body_scene(const json& mesh) {
  return {{"format", "stoss-scene/1"},
          {"bodies", {{{"name", "block"}, {"mesh", mesh}, {"material", material}}}},
          {"time", {{"step", 0.01}, {"end", 0.02}}}};
}

const std::string cube_nodes =
    "*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n";

/// The model with its end time cut to `steps` steps.
model::Model first_steps(model::Model m, int steps) {
  m.time.end = steps * m.time.step;
  return m;
}

Eigen::Vector3d mean_velocity(const model::Model& m, const model::Frame& f, int body) {
  const auto& b = m.mesh.bodies[body];
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (int n = b.node_begin; n < b.node_end; ++n) v += f.velocity.segment<3>(3 * n);
  return v / (b.node_end - b.node_begin);
}

// ---------------------------------------------------------------------------------------- examples

TEST(FileMeshExamples, CalculixDeckBallAndPlateRunIntoContact) {
  // api/examples/ball_plate_inp.json: the ball is ELSET EBALL, the plate ELSET EPLATE of one deck; the
  // surfaces keep the deck's names.
  const model::Model m = scene::load_file((examples / "ball_plate_inp.json").string());
  ASSERT_EQ(m.mesh.bodies.size(), 2u);
  EXPECT_EQ(m.mesh.bodies[0].element_end - m.mesh.bodies[0].element_begin, 96);  // 6 × 4 × 4 shell cells
  EXPECT_EQ(m.mesh.bodies[1].element_end - m.mesh.bodies[1].element_begin, 64);  // 8 × 8 × 1
  EXPECT_EQ(m.mesh.node_count(), 2 * (6 * 16 + 2) + 9 * 9 * 2);
  EXPECT_EQ(m.mesh.surface("ball/SBALL").size(), 96u);
  EXPECT_EQ(m.mesh.surface("plate/SPLATE").size(), 64u);
  EXPECT_THROW(m.mesh.surface("ball/SPLATE"), std::out_of_range);  // SPLATE has no face on the ball
  EXPECT_EQ(m.contact.at(0).slave, "ball/SBALL");
  // The outer faces of the ball point away from its centre (0, 0, 1.05).
  for (const mesh::Quad& q : m.mesh.surface("ball/SBALL")) {
    const auto& x = m.mesh.nodes;
    const Eigen::Vector3d n = (x[q[1]] - x[q[0]]).cross(x[q[3]] - x[q[0]]);
    EXPECT_GT(n.dot(x[q[0]] - Eigen::Vector3d(0, 0, 1.05)), 0);
  }

  // 0.05 above the plate at 1 per second: contact from about step 5; 14 steps, written to a result.
  TempDir dir;
  testing::RecordingObserver r;
  output::ResultWriter writer(dir.path);
  model::ObserverList both({&r, &writer});
  model::Model short_run = first_steps(m, 14);
  short_run.output.every = 7;
  const model::Summary s = simulate(short_run, both);
  ASSERT_TRUE(s.completed);
  EXPECT_GT(r.contact_window().first, 0.02);
  EXPECT_GT(r.contact_window().second, 0.1);
  // Free bodies, no gravity: the impact moves momentum from the ball to the plate, the sum stays.
  EXPECT_LT(r.vector_drift("linear_momentum"), 1e-9);
  const Eigen::Vector3d ball = mean_velocity(m, r.frames.back(), 0),
                        plate = mean_velocity(m, r.frames.back(), 1);
  EXPECT_GT(ball.z(), -0.95);   // slowed by the plate
  EXPECT_LT(plate.z(), -0.01);  // pushed down
  EXPECT_LT(s.max_penetration, 1e-3);

  // The result names the bodies and the deck's surfaces, and meshio reads it (values equal to HDF5).
  const output::ResultFile file = output::ResultFile::open(dir.path / output::result_file_name);
  EXPECT_EQ(file.body_names(), (std::vector<std::string>{"ball", "plate"}));
  const auto surfaces = file.surfaces();
  EXPECT_EQ(surfaces.at("ball/SBALL").rows(), 96);
  EXPECT_EQ(surfaces.at("plate/SPLATE").rows(), 64);
  ASSERT_EQ(file.frame_count(), 3);
  EXPECT_GT(file.frame_von_mises(2).maxCoeff(), 0);
  EXPECT_GT(file.frame_contact_pressure(2).maxCoeff(), 0);
  std::string python;
  for (const char* p : {"/usr/bin/python3", "python3"})
    if (python.empty() &&
        std::system((std::string(p) + " -c 'import meshio, h5py' > /dev/null 2>&1").c_str()) == 0)
      python = p;
  if (python.empty()) {
    GTEST_SKIP() << "python3-meshio (with python3-h5py) is not installed; deploy/packages.txt installs both";
  }
  const std::string command = python + " '" + STOSS_SOURCE_DIR + "/tests/core/output/meshio_check.py' '" +
                              dir.path.string() + "' 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  std::array<char, 4096> buffer;
  while (size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) out.append(buffer.data(), n);
  ASSERT_EQ(::pclose(pipe), 0) << out;
  const json report = json::parse(out);
  EXPECT_EQ(report["points"], m.mesh.node_count());
  EXPECT_EQ(report["cells"], 160);
  EXPECT_EQ(report["frames"], 3);
  EXPECT_GT(report["values_compared"].get<long>(), 3 * 358 * 10);
  EXPECT_EQ(report["last_von_mises_max"].get<double>(), file.frame_von_mises(2).maxCoeff());
}

TEST(FileMeshExamples, GmshPartWithAHoleFallsOnTheClampedPlate) {
  // api/examples/holed_part_plate.json: physical volumes "part" and "plate" of one .msh; physical surfaces
  // "bottom" and "top" hold faces of both bodies, and each body gets its own.
  const model::Model m = scene::load_file((examples / "holed_part_plate.json").string());
  ASSERT_EQ(m.mesh.bodies.size(), 2u);
  EXPECT_EQ(m.mesh.bodies[0].element_end - m.mesh.bodies[0].element_begin, 4 * 4 * 3 * 2);
  EXPECT_EQ(m.mesh.bodies[1].element_end - m.mesh.bodies[1].element_begin, 64);
  EXPECT_EQ(m.mesh.surface("part/bottom").size(), 48u);
  EXPECT_EQ(m.mesh.surface("part/top").size(), 48u);
  EXPECT_EQ(m.mesh.surface("plate/top").size(), 64u);
  EXPECT_EQ(m.mesh.surface("plate/bottom").size(), 64u);
  // The hole: no node of the part within the radius 0.3 of the axis; the part is turned by 30°.
  const auto& part = m.mesh.bodies[0];
  double corner_angle = 0;
  for (int n = part.node_begin; n < part.node_end; ++n) {
    const Eigen::Vector3d& x = m.mesh.nodes[n];
    EXPECT_GT(x.head<2>().norm(), 0.3 - 1e-9);
    if (x.head<2>().norm() > 0.6 * std::sqrt(2.0) - 1e-9 && x.x() > 0 && x.y() > 0)
      corner_angle = std::atan2(x.y(), x.x()) * 180 / M_PI;
  }
  EXPECT_NEAR(corner_angle, 45 + 30, 1e-9);

  testing::RecordingObserver r;
  const model::Summary s = simulate(first_steps(m, 10), r);
  ASSERT_TRUE(s.completed);
  EXPECT_GT(r.contact_window().first, 0);
  // The clamped plate pushes back: the part's downward momentum shrinks.
  const std::vector<double> pz = r.series("linear_momentum", 2);
  EXPECT_LT(pz.front(), 0);
  EXPECT_GT(pz.back(), pz.front() * 0.9);
  EXPECT_LT(s.max_penetration, 1e-3);
}

// ---------------------------------------------------------------------------------------- scenes

TEST(FileMeshScene, PathIsRelativeToTheSceneFileNotTheWorkingDirectory) {
  TempDir dir;
  dir.write("parts/cube.inp",
            cube_nodes + "*ELEMENT, TYPE=C3D8R, ELSET=E\n1,1,2,3,4,5,6,7,8\n*SURFACE, NAME=SB\nE, S1\n");
  json scene = one_body_scene({{"file", "cube.inp"},
                               {"elements", "E"},
                               {"transform", {{"translate", {1, 2, 3}}, {"scale", {2, 1, 1}}}}});
  const fs::path file = dir.write("parts/scene.json", scene.dump());
  const model::Model m = scene::load_file(file.string());
  EXPECT_EQ(m.mesh.node_count(), 8);
  EXPECT_EQ(m.mesh.nodes[6], Eigen::Vector3d(3, 3, 4));
  EXPECT_EQ(m.mesh.surface("block/SB").size(), 1u);
  EXPECT_EQ(m.mesh.surface("block/boundary").size(), 6u);
  EXPECT_EQ(m.scene["bodies"][0]["mesh"]["file"], "cube.inp");  // the scene as written, not a resolved path
}

TEST(FileMeshScene, ElementsTheFileLeavesOutAreAWarningAtTheBodysMesh) {
  // A line element (T3D2) and a quadrangle that is no face of the hexahedron: read, skipped, warned about.
  TempDir dir;
  const std::string hex = cube_nodes + "*ELEMENT, TYPE=C3D8R, ELSET=E\n1,1,2,3,4,5,6,7,8\n";
  dir.write("cube.inp",
            hex + "*ELEMENT, TYPE=T3D2, ELSET=L\n2,1,7\n*ELEMENT, TYPE=CPS4, ELSET=Q\n3,1,2,7,8\n");
  dir.write("clean.inp", hex);
  const auto warnings_of = [&](const std::string& file) {
    const fs::path scene =
        dir.write(file + ".json", one_body_scene({{"file", file}, {"elements", "E"}}).dump());
    return scene::summarize(scene::load_file(scene.string())).warnings;
  };
  const auto warned = warnings_of("cube.inp");
  ASSERT_EQ(warned.size(), 1u);
  EXPECT_EQ(warned[0].code, "mesh_elements_skipped");
  EXPECT_EQ(warned[0].pointer, "/bodies/0/mesh");
  EXPECT_NE(warned[0].message.find("2 2D/1D elements (CPS4, T3D2)"), std::string::npos) << warned[0].message;
  EXPECT_NE(warned[0].message.find("2 skipped"), std::string::npos) << warned[0].message;
  EXPECT_TRUE(warnings_of("clean.inp").empty());
}

TEST(FileMeshScene, ABoundaryEntryMayNameAnNsetAndItsNodesStayPut) {
  // A cube under gravity held by the node set of its base (no surface of that name): the base stays, the
  // top falls; a name that is neither lists the surfaces and the node sets (issue 25 §4).
  TempDir dir;
  dir.write("cube.inp",
            cube_nodes + "*ELEMENT, TYPE=C3D8R, ELSET=E\n1,1,2,3,4,5,6,7,8\n*NSET, NSET=NBASE\n1,2,3,4\n");
  json scene = one_body_scene({{"file", "cube.inp"}});
  scene["gravity"] = {0, 0, -10};
  scene["boundary"] = {{{"surface", "block/NBASE"}, {"fix", "xyz"}}};
  const model::Model m = scene::load_file(dir.write("held.json", scene.dump()).string());
  testing::RecordingObserver r;
  ASSERT_TRUE(simulate(m, r).completed);
  const Eigen::VectorXd& x = r.frames.back().position;
  for (int node = 0; node < 4; ++node) EXPECT_EQ(x.segment<3>(3 * node), m.mesh.nodes[node]) << node;
  for (int node = 4; node < 8; ++node) EXPECT_LT(x[3 * node + 2], 1.0) << "node " << node << " falls";
  scene["boundary"][0]["surface"] = "block/NTOP";
  EXPECT_EQ(issues_of(dir.write("wrong.json", scene.dump())),
            "/boundary/0/surface: body \"block\" has no surface or node set \"NTOP\" (it has boundary; node "
            "sets NBASE)");
  scene["boundary"] = json::array();  // a load needs faces: a node set is no surface there
  scene["loads"] = {{{"surface", "block/NBASE"}, {"pressure", 1}}};
  EXPECT_NE(issues_of(dir.write("load.json", scene.dump())).find("has no surface \"NBASE\""),
            std::string::npos);
}

TEST(FileMeshScene, ScenesWithoutAFileCannotNameMeshFiles) {
  // The HTTP API loads JSON bodies: a mesh file there would be a path on the server's disk.
  try {
    scene::load(one_body_scene({{"file", "/etc/passwd.inp"}}));
    FAIL() << "loaded";
  } catch (const scene::SceneError& e) {
    ASSERT_EQ(e.issues.size(), 1u);
    EXPECT_EQ(e.issues[0].pointer, "/bodies/0/mesh/file");
    EXPECT_NE(e.issues[0].message.find("mesh files are read only for a scene given as a file"),
              std::string::npos);
  }
}

TEST(FileMeshScene, BadMeshFilesAreIssuesNamingFileAndLineOrElement) {
  TempDir dir;
  const auto issues = [&](const std::string& deck, const json& mesh) {
    dir.write("bad.inp", deck);
    return issues_of(dir.write("scene.json", one_body_scene(mesh).dump()));
  };
  const json file = {{"file", "bad.inp"}};
  // Inverted: the bottom face listed clockwise.
  EXPECT_EQ(
      issues(cube_nodes + "*ELEMENT, TYPE=C3D8\n7,1,4,3,2,5,8,7,6\n", file),
      "/bodies/0/mesh/file: bad.inp:11: element 7: inverted or degenerate hexahedron, det J0 = -0.125 at a "
      "Gauss point (must be > 0; check the node order)");
  // Degenerate: the top face on the bottom one.
  EXPECT_NE(issues(cube_nodes + "*ELEMENT, TYPE=C3D8\n7,1,2,3,4,1,2,3,4\n", file)
                .find("bad.inp:11: element 7: inverted or degenerate hexahedron"),
            std::string::npos);
  EXPECT_EQ(issues(cube_nodes + "*ELEMENT, TYPE=C3D10\n1,1,2,3,4,5,6,7,8,1,2\n", file),
            "/bodies/0/mesh/file: bad.inp:10: unsupported element type C3D10; Stoss reads 8-node hexahedra "
            "(C3D8, C3D8R)");
  EXPECT_EQ(issues(cube_nodes + "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7\n", file),
            "/bodies/0/mesh/file: bad.inp:11: element 1 has 7 nodes, C3D8 needs 8");
  EXPECT_EQ(issues(cube_nodes + "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7,8\n1,1,2,3,4,5,6,7,8\n", file),
            "/bodies/0/mesh/file: bad.inp:12: duplicate element id 1 (first defined on line 11)");
  EXPECT_EQ(issues(cube_nodes + "*ELEMENT, TYPE=C3D8, ELSET=E\n1,1,2,3,4,5,6,7,8\n",
                   {{"file", "bad.inp"}, {"elements", "EBALL"}}),
            "/bodies/0/mesh/file: bad.inp: has no element set 'EBALL' (it has E)");
  EXPECT_EQ(issues(cube_nodes, file), "/bodies/0/mesh/file: bad.inp: has no 8-node hexahedra");
  EXPECT_EQ(issues_of(dir.write("scene.json", one_body_scene({{"file", "missing.msh"}}).dump())),
            "/bodies/0/mesh/file: missing.msh: cannot read the file");
  EXPECT_EQ(issues(cube_nodes + "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7,8\n",
                   {{"file", "bad.inp"},
                    {"transform", {{"scale", -1}, {"rotate", {{"axis", {0, 0, 0}}, {"degrees", 10}}}}}}),
            "/bodies/0/mesh/transform/rotate/axis: must not be the zero vector\n"
            "/bodies/0/mesh/transform/scale: must be > 0, got -1");
  EXPECT_EQ(issues_of(dir.write(
                "scene.json",
                one_body_scene({{"box", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}, {"divisions", {1, 1, 1}}}},
                                {"elements", "E"}})
                    .dump())),
            "/bodies/0/mesh/elements: only for a mesh read from a file (\"file\" or \"id\")");
}

TEST(FileMeshScene, AnIdIsReadFromTheStoreTheCallerGivesAndOnlyFromIt) {
  TempDir dir;
  const fs::path stored =
      dir.write("store/cube.inp", cube_nodes + "*ELEMENT, TYPE=C3D8, ELSET=E\n1,1,2,3,4,5,6,7,8\n");
  const std::string id(64, 'a');
  scene::MeshFiles files;
  files.stored = [&](const std::string& asked) { return asked == id ? std::optional(stored) : std::nullopt; };
  const model::Model m = scene::load(
      one_body_scene({{"id", id}, {"elements", "E"}, {"transform", {{"translate", {0, 0, 5}}}}}), files);
  EXPECT_EQ(m.mesh.node_count(), 8);
  EXPECT_EQ(m.mesh.nodes[6], Eigen::Vector3d(1, 1, 6));
  EXPECT_EQ(m.scene["bodies"][0]["mesh"]["id"], id);  // the scene keeps the id, never a path
  const auto issues = [&](const json& mesh, const scene::MeshFiles& where) {
    try {
      scene::load(one_body_scene(mesh), where);
    } catch (const scene::SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(issues({{"id", std::string(64, 'b')}}, files),
            "/bodies/0/mesh/id: no mesh with this id; POST it to /v1/meshes first");
  EXPECT_EQ(issues({{"id", "../store/cube"}}, files),
            "/bodies/0/mesh/id: must be 64 lowercase hex digits (the id POST /v1/meshes answers), got "
            "\"../store/cube\"");
  EXPECT_NE(issues({{"id", id}}, {}).find("/bodies/0/mesh/id: mesh ids name meshes stored by the service"),
            std::string::npos);
  EXPECT_EQ(issues({{"id", id}, {"file", "cube.inp"}}, files),
            "/bodies/0/mesh: exactly one of box, hollow_sphere, nodes+hex8, file, id");
}

TEST(FileMeshScene, ContactPairNamingAnEmptyOrMissingGroupIsAnIssue) {
  TempDir dir;
  fs::copy_file(examples / "meshes/ball_plate.inp", dir.path / "deck.inp");
  json scene = json::parse(std::ifstream(examples / "ball_plate_inp.json"));
  for (json& b : scene["bodies"]) b["mesh"]["file"] = "deck.inp";
  // SPLATE exists in the deck but has no face on EBALL; SNONE does not exist at all.
  scene["contact"][0]["slave"] = "ball/SPLATE";
  scene["contact"].push_back({{"slave", "ball/SNONE"}, {"master", "plate/SPLATE"}});
  EXPECT_EQ(
      issues_of(dir.write("scene.json", scene.dump())),
      "/contact/0/slave: body \"ball\" has no surface \"SPLATE\" (it has SBALL, boundary); deck.inp defines "
      "surface 'SPLATE', but none of its faces is on an element of 'EBALL'\n"
      "/contact/1/slave: body \"ball\" has no surface \"SNONE\" (it has SBALL, boundary)");
  // An empty physical group of a Gmsh file is named the same way.
  scene = json::parse(std::ifstream(examples / "holed_part_plate.json"));
  fs::copy_file(examples / "meshes/holed_part_plate.msh", dir.path / "part.msh");
  for (json& b : scene["bodies"]) b["mesh"]["file"] = "part.msh";
  scene["bodies"][0]["mesh"]["elements"] = "nothing";
  EXPECT_EQ(issues_of(dir.write("scene.json", scene.dump())),
            "/bodies/0/mesh/file: part.msh: has no element set 'nothing' (it has part, plate)");
}

// Issue 20: what passed validation and then failed in the run is refused at validation.

TEST(FileMeshScene, SurfacesThatTheResultFileWouldWriteUnderOneNameAreRefusedWithBothNames) {
  TempDir dir;
  dir.write("names.inp", cube_nodes +
                             "*ELEMENT, TYPE=C3D8, ELSET=E\n1,1,2,3,4,5,6,7,8\n*SURFACE, NAME=a/b\n1, S1\n"
                             "*SURFACE, NAME=a_b\n1, S2\n");
  EXPECT_EQ(
      issues_of(dir.write("scene.json", one_body_scene({{"file", "names.inp"}}).dump())),
      "/bodies/0/mesh/file: names.inp: surfaces 'a/b' and 'a_b' would both be written as 'a_b' in the result "
      "file (names there hold no '/' and start with no '.'); rename one");
  dir.write("dots.inp", cube_nodes +
                            "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7,8\n*SURFACE, NAME=.x\n1, S1\n"
                            "*SURFACE, NAME=_.x\n1, S2\n");
  EXPECT_NE(issues_of(dir.write("scene.json", one_body_scene({{"file", "dots.inp"}}).dump()))
                .find("surfaces '.x' and '_.x' would both be written as '_.x'"),
            std::string::npos);
}

TEST(FileMeshScene, ElementsWhoseVolumeIsInfiniteOrSubnormalAreRefusedNamingTheElement) {
  TempDir dir;
  const auto scaled_cube = [](const std::string& unit) {
    return "*NODE\n1,0,0,0\n2," + unit + ",0,0\n3," + unit + "," + unit + ",0\n4,0," + unit + ",0\n5,0,0," +
           unit + "\n6," + unit + ",0," + unit + "\n7," + unit + "," + unit + "," + unit + "\n8,0," + unit +
           "," + unit + "\n*ELEMENT, TYPE=C3D8\n12,1,2,3,4,5,6,7,8\n";
  };
  dir.write("huge.inp", scaled_cube("1e200"));
  EXPECT_EQ(issues_of(dir.write("scene.json", one_body_scene({{"file", "huge.inp"}}).dump())),
            "/bodies/0/mesh/file: huge.inp:11: element 12: det J0 = inf at a Gauss point: the element's "
            "volume is not "
            "a finite number (coordinates too large? scale the mesh)");
  dir.write("tiny.inp", scaled_cube("1e-105"));
  EXPECT_EQ(
      issues_of(dir.write("scene.json", one_body_scene({{"file", "tiny.inp"}}).dump())),
      "/bodies/0/mesh/file: tiny.inp:11: element 12: det J0 = 1.25e-316 at a Gauss point is below the "
      "smallest "
      "normal double (2.2e-308): the element is too small to compute with (coordinates too small? scale the "
      "mesh)");
  // Inline meshes and boxes by the same rule.
  json cube = {{"nodes",
                {{0, 0, 0},
                 {1e200, 0, 0},
                 {1e200, 1e200, 0},
                 {0, 1e200, 0},
                 {0, 0, 1e200},
                 {1e200, 0, 1e200},
                 {1e200, 1e200, 1e200},
                 {0, 1e200, 1e200}}},
               {"hex8", {{0, 1, 2, 3, 4, 5, 6, 7}}}};
  EXPECT_EQ(
      issues_of(dir.write("scene.json", one_body_scene(cube).dump())),
      "/bodies/0/mesh/hex8/0: det J0 = inf at a Gauss point: the element's volume is not a finite number "
      "(coordinates too large? scale the mesh)");
  for (const json& sphere : {json{{"outer_radius", 1e200}, {"inner_radius", 1e199}},
                             json{{"outer_radius", 1e-105}, {"inner_radius", 1e-106}},
                             json{{"center", {1e200, 0, 0}}, {"outer_radius", 1}, {"inner_radius", 0.5}}}) {
    SCOPED_TRACE(sphere.dump());
    EXPECT_EQ(issues_of(dir.write("scene.json", one_body_scene({{"hollow_sphere", sphere}}).dump()))
                  .find("/bodies/0/mesh/hollow_sphere: its elements would be unusable: "),
              0u);
  }
  const json wide = {{"outer_radius", 1e10}, {"inner_radius", 1e-10}, {"divisions", 40}};
  EXPECT_EQ(issues_of(dir.write("scene.json", one_body_scene({{"hollow_sphere", wide}}).dump())), "");
  const json box = {
      {"box", {{"min", {0, 0, 0}}, {"max", {1e-105, 1e-105, 1e-105}}, {"divisions", {1, 1, 1}}}}};
  EXPECT_NE(issues_of(dir.write("scene.json", one_body_scene(box).dump()))
                .find("/bodies/0/mesh/box: its elements would be unusable: det J0 = 1.25e-316 at a Gauss "
                      "point is below the "
                      "smallest normal double"),
            std::string::npos);
}

TEST(FileMeshScene, AStoredMeshIsSelfContainedAndItsParsedFormIsUsedWhenGiven) {
  TempDir dir;
  dir.write("store/nodes.inp", cube_nodes.substr(6));
  const fs::path stored = dir.write("store/with_include.inp",
                                    "*NODE\n*INCLUDE, INPUT=nodes.inp\n*ELEMENT, TYPE=C3D8\n"
                                    "1,1,2,3,4,5,6,7,8\n");
  const std::string id(64, 'c');
  scene::MeshFiles files;
  files.stored = [&](const std::string&) { return std::optional(stored); };
  try {
    scene::load(one_body_scene({{"id", id}}), files);
    FAIL() << "a stored mesh with *INCLUDE loaded";
  } catch (const scene::SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "/bodies/0/mesh/id: mesh " + id +
                  ":2: *INCLUDE is not accepted here: an uploaded mesh must be "
                  "self-contained (its id is the hash of its bytes); put the included lines in their place");
  }
  // With `parsed`, the store's parsed form is used: validation and the build ask for it, the file is not
  // read.
  int asked = 0;
  files.stored = nullptr;
  const auto parsed = std::make_shared<const mesh::ImportedMesh>(mesh::parse_abaqus(
      cube_nodes + "*ELEMENT, TYPE=C3D8\n1,1,2,3,4,5,6,7,8\n", "mesh " + id, mesh::upload_limits(100)));
  files.parsed = [&](const std::string& asked_id) {
    ++asked;
    return asked_id == id ? parsed : nullptr;
  };
  EXPECT_EQ(scene::load(one_body_scene({{"id", id}}), files).mesh.node_count(), 8);
  EXPECT_EQ(asked, 2);
}

}  // namespace
}  // namespace stoss
