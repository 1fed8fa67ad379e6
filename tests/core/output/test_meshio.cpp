// The result opens in the usual Python route: Debian's python3-meshio reads result_mesh.xdmf with
// meshio.read and result.xdmf with meshio.xdmf.TimeSeriesReader, and every value it reads equals the
// HDF5 dataset (tests/core/output/meshio_check.py compares them with h5py).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "core/output/result_reader.hpp"
#include "core/output/result_writer.hpp"
#include "output_test_utils.hpp"

namespace stoss::output {
namespace {

/// A python3 that imports meshio and h5py ("" if none): Debian's first (a pyenv shim may come first on PATH).
std::string python_with_meshio() {
  for (const char* python : {"/usr/bin/python3", "python3"})
    if (std::system((std::string(python) + " -c 'import meshio, h5py' > /dev/null 2>&1").c_str()) == 0)
      return python;
  return "";
}

/// stdout of a command and its exit status.
std::pair<std::string, int> run(const std::string& command) {
  std::string out;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return {"", -1};
  std::array<char, 4096> buffer;
  while (size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) out.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  return {out, WIFEXITED(status) ? WEXITSTATUS(status) : -1};
}

class Meshio : public testing::OutputDirectory {};

TEST_F(Meshio, ReadsMeshAndTimeSeriesWithTheValuesOfTheHdf5File) {
  const std::string python = python_with_meshio();
  if (python.empty())
    GTEST_SKIP() << "python3-meshio (with python3-h5py) is not installed; deploy/packages.txt installs both";
  const model::Model m = testing::tiny_model();
  {
    ResultWriter writer(dir);
    testing::play_tiny_run(writer, m);
    writer.end(testing::summary(true));
  }
  const auto [out, status] = run(python + " '" + STOSS_SOURCE_DIR + "/tests/core/output/meshio_check.py' '" +
                                 dir.string() + "' 2>&1");
  ASSERT_EQ(status, 0) << out;
  const nlohmann::json report = nlohmann::json::parse(out);
  EXPECT_EQ(report["points"], 16);
  EXPECT_EQ(report["cells"], 2);
  EXPECT_EQ(report["frames"], 3);
  EXPECT_EQ(report["fields"],
            (nlohmann::json{"cauchy_stress", "contact_pressure", "displacement", "velocity", "von_mises"}));
  // Mesh: 48 + 16 + 2 + 16; time series: 48 + 16; per frame 48 + 48 + 16 + 12 + 2.
  EXPECT_EQ(report["values_compared"], 82 + 64 + 3 * 126);
  const ResultFile file = ResultFile::open(dir / result_file_name);
  EXPECT_EQ(report["last_time"].get<double>(), file.frame_times()[2]);
  const double sum = file.frame_displacements(2).col(0).sum();  // summed in another order by numpy
  EXPECT_NEAR(report["last_displacement_x_sum"].get<double>(), sum, 1e-12 * std::abs(sum));
  EXPECT_EQ(report["last_von_mises_max"].get<double>(), file.frame_von_mises(2).maxCoeff());
}

}  // namespace
}  // namespace stoss::output
