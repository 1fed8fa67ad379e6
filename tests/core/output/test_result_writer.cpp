#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/output/result_reader.hpp"
#include "core/output/result_writer.hpp"
#include "output_test_utils.hpp"

namespace stoss::output {
namespace {

using testing::OutputDirectory;
namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class ResultWriterTest : public OutputDirectory {
 protected:
  /// Plays the tiny run and ends it; returns the model.
  model::Model write_tiny(bool completed, bool with_pressure = true) {
    const model::Model m = testing::tiny_model();
    ResultWriter writer(dir);
    testing::play_tiny_run(writer, m, with_pressure);
    writer.end(testing::summary(completed));
    return m;
  }
};

// The writer shall store every series row exactly, in layout order, across buffer flushes.
TEST_F(ResultWriterTest, CompletedRunStoresEverySeriesRowExactly) {
  write_tiny(true);
  const ResultFile file = ResultFile::open(dir / result_file_name);
  EXPECT_EQ(file.series_names(), (std::vector<std::string>{"time", "kinetic_energy", "total_energy",
                                                           "linear_momentum", "newton_iterations"}));
  const Eigen::MatrixXd time = file.series("time"), ke = file.series("kinetic_energy"),
                        te = file.series("total_energy"), lm = file.series("linear_momentum"),
                        it = file.series("newton_iterations");
  ASSERT_EQ(time.rows(), testing::tiny_steps);
  ASSERT_EQ(time.cols(), 1);
  ASSERT_EQ(lm.rows(), testing::tiny_steps);
  ASSERT_EQ(lm.cols(), 3);
  ASSERT_EQ(it.rows(), testing::tiny_steps);
  for (int s = 0; s < testing::tiny_steps; ++s) {
    const model::StepRow row = testing::tiny_row(s);
    EXPECT_EQ(time(s, 0), row.time) << "step " << s;
    EXPECT_EQ(ke(s, 0), row.values[0]) << "step " << s;
    EXPECT_EQ(te(s, 0), row.values[1]) << "step " << s;
    EXPECT_EQ(lm.row(s), Eigen::RowVector3d(row.values[2], row.values[3], row.values[4])) << "step " << s;
    EXPECT_EQ(it(s, 0), row.values[5]) << "step " << s;
  }
  EXPECT_TRUE(file.series_is_integer("newton_iterations"));
  EXPECT_FALSE(file.series_is_integer("kinetic_energy"));
}

// The root attributes shall describe the run (docs/results.md) and mark it complete.
TEST_F(ResultWriterTest, CompletedRunHasRootAttributes) {
  const model::Model m = write_tiny(true);
  const ResultFile file = ResultFile::open(dir / result_file_name);
  EXPECT_EQ(file.attribute_string("format"), "stoss-result/2");
  EXPECT_FALSE(file.attribute_string("stoss_version").empty());
  EXPECT_EQ(file.attribute_string("scheme"), "energy_momentum");
  EXPECT_EQ(file.attribute_double("step"), 0.01);
  EXPECT_EQ(file.attribute_double("end"), 1.29);
  EXPECT_EQ(file.attribute_strings("effects"), m.effects);
  EXPECT_EQ(nlohmann::json::parse(file.attribute_string("scene")), m.scene);
  EXPECT_EQ(file.attribute_double("complete"), 1.0);
  EXPECT_EQ(file.attribute_double("wall_seconds"), 1.5);
}

// /mesh shall hold the reference nodes, the 0-based connectivity and the body of each element.
TEST_F(ResultWriterTest, CompletedRunStoresMesh) {
  const model::Model m = write_tiny(true);
  const ResultFile file = ResultFile::open(dir / result_file_name);
  const Eigen::MatrixXd nodes = file.mesh_nodes();
  ASSERT_EQ(nodes.rows(), 16);
  ASSERT_EQ(nodes.cols(), 3);
  for (int i = 0; i < 16; ++i) EXPECT_EQ(nodes.row(i).transpose(), m.mesh.nodes[i]) << "node " << i;
  const auto hex8 = file.mesh_hex8();
  ASSERT_EQ(hex8.rows(), 2);
  for (int e = 0; e < 2; ++e)
    for (int a = 0; a < 8; ++a) EXPECT_EQ(hex8(e, a), m.mesh.hex8[e][a]);
  EXPECT_EQ(hex8(1, 0), 8);  // the second body's nodes are renumbered after the first's
  EXPECT_EQ(file.body_names(), (std::vector<std::string>{"ball", "wall"}));
  EXPECT_EQ(file.element_bodies(), Eigen::Vector2i(0, 1));
  Eigen::VectorXi node_body(16);
  node_body << 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1;
  EXPECT_EQ(file.node_bodies(), node_body);
  // The named surfaces, under their "body/surface" names, in global node numbers.
  const auto surfaces = file.surfaces();
  ASSERT_EQ(surfaces.size(), 2u);
  const auto& wall = surfaces.at("wall/all");
  ASSERT_EQ(wall.rows(), 6);
  for (int f = 0; f < 6; ++f)
    for (int a = 0; a < 4; ++a) EXPECT_EQ(wall(f, a), m.mesh.surface("wall/all")[f][a]);
}

// /frames shall hold each frame's time, positions, velocities and contact pressure.
TEST_F(ResultWriterTest, CompletedRunStoresFrames) {
  const model::Model m = write_tiny(true);
  const ResultFile file = ResultFile::open(dir / result_file_name);
  ASSERT_EQ(file.frame_count(), 3);
  EXPECT_EQ(file.frame_times(), Eigen::Vector3d(0.0, 0.64, 1.29));
  ASSERT_TRUE(file.has_contact_pressure());
  for (int k = 0; k < 3; ++k) {
    const model::Frame expected = testing::tiny_frame(m, k, true);
    const Eigen::MatrixXd x = file.frame_positions(k), v = file.frame_velocities(k);
    ASSERT_EQ(x.rows(), 16);
    ASSERT_EQ(x.cols(), 3);
    for (int i = 0; i < 16; ++i) {
      EXPECT_EQ(x.row(i).transpose(), expected.position.segment<3>(3 * i)) << "frame " << k << " node " << i;
      EXPECT_EQ(v.row(i).transpose(), expected.velocity.segment<3>(3 * i)) << "frame " << k << " node " << i;
    }
    EXPECT_EQ(file.frame_contact_pressure(k), expected.contact_pressure) << "frame " << k;
    // displacement = position − reference position, exactly as subtracted.
    const Eigen::MatrixXd u = file.frame_displacements(k);
    for (int i = 0; i < 16; ++i)
      EXPECT_EQ(u.row(i).transpose(), expected.position.segment<3>(3 * i) - m.mesh.nodes[i]) << "frame " << k;
  }
  EXPECT_THROW(file.frame_positions(3), std::out_of_range);
  EXPECT_THROW(file.frame_positions(-1), std::out_of_range);
}

// Stresses: the tiny frames move node i by 0.001·i·k along every axis, so frame 0 is unstressed and
// frame 2 is not; von Mises agrees with the stored Cauchy stress.
TEST_F(ResultWriterTest, FramesCarryElementStress) {
  write_tiny(true);
  const ResultFile file = ResultFile::open(dir / result_file_name);
  ASSERT_TRUE(file.has_stress());
  EXPECT_LT(file.frame_von_mises(0).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT(file.frame_cauchy_stress(0).cwiseAbs().maxCoeff(), 1e-9);
  const Eigen::MatrixXd sigma = file.frame_cauchy_stress(2);
  const Eigen::VectorXd vm = file.frame_von_mises(2);
  ASSERT_EQ(sigma.rows(), 2);
  ASSERT_EQ(sigma.cols(), 6);
  for (int e = 0; e < 2; ++e) {
    const double xx = sigma(e, 0), xy = sigma(e, 1), xz = sigma(e, 2), yy = sigma(e, 3), yz = sigma(e, 4),
                 zz = sigma(e, 5);
    const double expected =
        std::sqrt(0.5 * ((xx - yy) * (xx - yy) + (yy - zz) * (yy - zz) + (zz - xx) * (zz - xx)) +
                  3 * (xy * xy + yz * yz + xz * xz));
    EXPECT_NEAR(vm[e], expected, 1e-9 * expected);
    EXPECT_GT(vm[e], 1.0);
  }
}

// A completed run shall leave result.h5 and result.xdmf, and no partial files.
TEST_F(ResultWriterTest, CompletedRunRenamesPartialFile) {
  write_tiny(true);
  EXPECT_TRUE(fs::exists(dir / result_file_name));
  EXPECT_TRUE(fs::exists(dir / xdmf_file_name));
  EXPECT_FALSE(fs::exists(dir / partial_file_name));
  EXPECT_FALSE(fs::exists(dir / incomplete_file_name));
  for (const auto& entry : fs::directory_iterator(dir))  // the sidecars' temporaries are renamed away too
    EXPECT_EQ(entry.path().extension() == ".tmp" || entry.path().extension() == ".partial", false)
        << entry.path();
}

// result.xdmf shall be well-formed XML pointing at result.h5, with one grid per frame.
TEST_F(ResultWriterTest, CompletedRunWritesXdmfSidecar) {
  write_tiny(true);
  const std::string xdmf = read_text(dir / xdmf_file_name);
  EXPECT_EQ(testing::xml_structure_error(xdmf), "");
  EXPECT_NE(xdmf.find("result.h5:/frames/2/position"), std::string::npos);
  EXPECT_EQ(xdmf.find("HyperSlab"), std::string::npos);
  EXPECT_NE(xdmf.find("result.h5:/mesh/hex8"), std::string::npos);
  EXPECT_NE(xdmf.find("CollectionType=\"Temporal\""), std::string::npos);
  EXPECT_EQ(testing::count_of(xdmf, "<Time "), 3);
  EXPECT_EQ(testing::count_of(xdmf, "<Time Value=\"1.29\"/>"), 1);
  EXPECT_EQ(testing::count_of(xdmf, "/contact_pressure</DataItem>"), 3);
  EXPECT_EQ(testing::count_of(xdmf, "/von_mises</DataItem>"), 3);
  const std::string mesh = read_text(dir / xdmf_mesh_file_name);
  EXPECT_EQ(testing::xml_structure_error(mesh), "");
  EXPECT_EQ(testing::count_of(mesh, "<Grid "), 1);
  EXPECT_NE(mesh.find("result.h5:/mesh/nodes"), std::string::npos);
}

// Without contact pressure in the frames, neither the file nor the sidecar shall carry it.
TEST_F(ResultWriterTest, FramesWithoutPressureHaveNoPressureDataset) {
  write_tiny(true, false);
  const ResultFile file = ResultFile::open(dir / result_file_name);
  EXPECT_EQ(file.frame_count(), 3);
  EXPECT_FALSE(file.has_contact_pressure());
  EXPECT_EQ(read_text(dir / xdmf_file_name).find("contact_pressure"), std::string::npos);
}

/// Chunk shape and maximum shape of a dataset, read with the bare HDF5 C API.
std::pair<std::vector<hsize_t>, std::vector<hsize_t>> chunk_and_max_dims(const fs::path& file,
                                                                         const char* name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
  const hid_t plist = H5Dget_create_plist(d), space = H5Dget_space(d);
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> chunk(rank), dims(rank), max_dims(rank);
  H5Pget_chunk(plist, rank, chunk.data());
  H5Sget_simple_extent_dims(space, dims.data(), max_dims.data());
  H5Sclose(space);
  H5Pclose(plist);
  H5Dclose(d);
  H5Fclose(f);
  return {chunk, max_dims};
}

// Series and frame times shall grow along their first dimension; each frame is a group of whole datasets.
TEST_F(ResultWriterTest, DatasetsAreChunkedAndExtendible) {
  write_tiny(true);
  const fs::path file = dir / result_file_name;
  EXPECT_EQ(chunk_and_max_dims(file, "/frames/time").second, (std::vector<hsize_t>{H5S_UNLIMITED}));
  EXPECT_EQ(chunk_and_max_dims(file, "/frames/1/position").second, (std::vector<hsize_t>{16, 3}));
  EXPECT_EQ(chunk_and_max_dims(file, "/frames/1/contact_pressure").second, (std::vector<hsize_t>{16}));
  const auto [momentum_chunk, momentum_max] = chunk_and_max_dims(file, "/series/linear_momentum");
  EXPECT_EQ(momentum_chunk.size(), 2u);
  EXPECT_EQ(momentum_max, (std::vector<hsize_t>{H5S_UNLIMITED, 3}));
}

// A canceled or failed run shall leave no result.h5, but result.incomplete.h5 with complete = 0.
TEST_F(ResultWriterTest, IncompleteRunLeavesNoResultFile) {
  write_tiny(false);
  EXPECT_FALSE(fs::exists(dir / result_file_name));
  EXPECT_FALSE(fs::exists(dir / partial_file_name));
  EXPECT_FALSE(fs::exists(dir / xdmf_file_name));
  ASSERT_TRUE(fs::exists(dir / incomplete_file_name));
  const ResultFile file = ResultFile::open(dir / incomplete_file_name);
  EXPECT_EQ(file.attribute_double("complete"), 0.0);
  EXPECT_EQ(file.attribute_double("wall_seconds"), 1.5);
  EXPECT_EQ(file.series("time").rows(), testing::tiny_steps);
}

// A writer destroyed without end() (an exception in the run) shall leave only the partial file.
TEST_F(ResultWriterTest, DestroyedWithoutEndLeavesOnlyPartialFile) {
  const model::Model m = testing::tiny_model();
  {
    ResultWriter writer(dir);
    writer.begin(m, testing::tiny_layout());
    for (int s = 0; s < 70; ++s) writer.step(testing::tiny_row(s));
    writer.frame(testing::tiny_frame(m, 0, true));
  }
  EXPECT_FALSE(fs::exists(dir / result_file_name));
  EXPECT_FALSE(fs::exists(dir / xdmf_file_name));
  ASSERT_TRUE(fs::exists(dir / partial_file_name));
  const ResultFile file = ResultFile::open(dir / partial_file_name);
  EXPECT_EQ(file.attribute_double("complete"), 0.0);
  EXPECT_EQ(file.series("time").rows(), ResultWriter::rows_per_flush);  // only whole flushes reached the file
  EXPECT_EQ(file.frame_count(), 1);
}

// A new run in a directory shall remove the earlier run's results before it writes.
TEST_F(ResultWriterTest, NewRunRemovesEarlierResults) {
  write_tiny(true);
  ASSERT_TRUE(fs::exists(dir / result_file_name));
  write_tiny(false);
  EXPECT_FALSE(fs::exists(dir / result_file_name));
  EXPECT_FALSE(fs::exists(dir / xdmf_file_name));
  EXPECT_FALSE(fs::exists(dir / xdmf_mesh_file_name));
  EXPECT_TRUE(fs::exists(dir / incomplete_file_name));
}

// end() without begin() (a run that failed before it started) shall write nothing.
TEST_F(ResultWriterTest, EndWithoutBeginWritesNothing) {
  ResultWriter writer(dir);
  writer.end(testing::summary(false));
  EXPECT_FALSE(fs::exists(dir));
}

TEST_F(ResultWriterTest, RejectsRowOfWrongSize) {
  ResultWriter writer(dir);
  writer.begin(testing::tiny_model(), testing::tiny_layout());
  model::StepRow row = testing::tiny_row(0);
  row.values.pop_back();
  try {
    writer.step(row);
    FAIL() << "a short row was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "step row has 5 values, the layout 6");
  }
}

TEST_F(ResultWriterTest, RejectsFrameOfWrongSize) {
  const model::Model m = testing::tiny_model();
  ResultWriter writer(dir);
  writer.begin(m, testing::tiny_layout());
  model::Frame frame = testing::tiny_frame(m, 0, true);
  frame.velocity.conservativeResize(45);
  try {
    writer.frame(frame);
    FAIL() << "a short velocity was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "frame field velocity has 45 values, expected 48");
  }
}

// The first frame decides whether the file carries contact pressure; later frames must agree.
TEST_F(ResultWriterTest, RejectsPressureAppearingAfterFirstFrame) {
  const model::Model m = testing::tiny_model();
  ResultWriter writer(dir);
  writer.begin(m, testing::tiny_layout());
  writer.frame(testing::tiny_frame(m, 0, false));
  EXPECT_THROW(writer.frame(testing::tiny_frame(m, 1, true)), std::invalid_argument);
}

TEST_F(ResultWriterTest, StepBeforeBeginIsALogicError) {
  ResultWriter writer(dir);
  EXPECT_THROW(writer.step(testing::tiny_row(0)), std::logic_error);
}

// HDF5 failures shall surface as std::runtime_error naming the file and the dataset.
TEST_F(ResultWriterTest, HdfErrorNamesFileAndDataset) {
  model::SeriesLayout layout = testing::tiny_layout();
  layout.series.push_back({"kinetic_energy"});  // a second dataset of the same name
  ResultWriter writer(dir);
  try {
    writer.begin(testing::tiny_model(), layout);
    FAIL() << "a duplicate series was accepted";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'/series/kinetic_energy'"), std::string::npos) << message;
    EXPECT_NE(message.find((dir / partial_file_name).string()), std::string::npos) << message;
  }
  EXPECT_FALSE(fs::exists(dir / result_file_name));
}

}  // namespace
}  // namespace stoss::output
