#include <gtest/gtest.h>

#include <sstream>

#include "core/output/result_reader.hpp"
#include "core/output/result_writer.hpp"
#include "output_test_utils.hpp"

namespace stoss::output {
namespace {

namespace fs = std::filesystem;

class ResultReaderTest : public testing::OutputDirectory {
 protected:
  void SetUp() override {
    OutputDirectory::SetUp();
    ResultWriter writer(dir);
    testing::play_tiny_run(writer, testing::tiny_model());
    writer.end(testing::summary(true));
    path = dir / result_file_name;
  }

  fs::path path;
};

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The CSV shall have a header naming every column (vectors as _x,_y,_z) and one line per step.
TEST_F(ResultReaderTest, CsvHasHeaderAndOneLinePerStep) {
  const auto lines = lines_of(series_csv(path));
  ASSERT_EQ(lines.size(), 1u + testing::tiny_steps);
  EXPECT_EQ(lines[0],
            "time,kinetic_energy,total_energy,linear_momentum_x,linear_momentum_y,linear_momentum_z,"
            "newton_iterations");
  EXPECT_EQ(lines[1], "0,1,1,0,-0,0,1");
  EXPECT_EQ(lines[4], "0.03,2.5,0.25,3,-6,0.75,4");
  EXPECT_EQ(lines.back(), "1.29,65.5,0.007692307692307693,129,-258,32.25,5");
}

// The JSON shall hold every series by name: scalars as numbers, vectors as triples, counts as integers.
TEST_F(ResultReaderTest, JsonHasEverySeriesWithItsShape) {
  const nlohmann::json j = series_json(path);
  ASSERT_EQ(j.size(), 5u);
  for (const char* name : {"time", "kinetic_energy", "total_energy", "linear_momentum", "newton_iterations"})
    ASSERT_EQ(j.at(name).size(), size_t(testing::tiny_steps)) << name;
  EXPECT_EQ(j["time"][3], 0.03);
  EXPECT_EQ(j["kinetic_energy"][0], 1.0);
  EXPECT_EQ(j["linear_momentum"][5], nlohmann::json({5.0, -10.0, 1.25}));
  EXPECT_TRUE(j["newton_iterations"][7].is_number_integer());
  EXPECT_EQ(j["newton_iterations"][7], 3);
  EXPECT_TRUE(j["total_energy"][0].is_number_float());
}

TEST_F(ResultReaderTest, MissingSeriesIsOutOfRange) {
  const ResultFile file = ResultFile::open(path);
  try {
    file.series("potential_energy");
    FAIL() << "an absent series was read";
  } catch (const std::out_of_range& e) {
    EXPECT_EQ(std::string(e.what()), "no series 'potential_energy' in " + path.string());
  }
}

TEST_F(ResultReaderTest, MissingAttributeIsOutOfRange) {
  const ResultFile file = ResultFile::open(path);
  EXPECT_FALSE(file.has_attribute("gravity"));
  EXPECT_THROW(file.attribute_double("gravity"), std::out_of_range);
  EXPECT_THROW(file.attribute_string("gravity"), std::out_of_range);
}

// A string array of more than one element is not a single string.
TEST_F(ResultReaderTest, StringArrayIsNotASingleString) {
  const ResultFile file = ResultFile::open(path);
  EXPECT_THROW(file.attribute_string("effects"), std::runtime_error);
}

// Opening a file that is not there shall name it in a std::runtime_error.
TEST_F(ResultReaderTest, OpeningMissingFileNamesIt) {
  const fs::path missing = dir / "nothing.h5";
  try {
    ResultFile::open(missing);
    FAIL() << "a missing file was opened";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
}

// A file that is not HDF5 shall be refused the same way, not crash the reader.
TEST_F(ResultReaderTest, OpeningNonHdfFileFails) {
  const fs::path text = dir / "result.xdmf";
  EXPECT_THROW(ResultFile::open(text), std::runtime_error);
  EXPECT_THROW(series_json(text), std::runtime_error);
}

}  // namespace
}  // namespace stoss::output
