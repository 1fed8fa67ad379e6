// The system shall report a job's own peak memory (issue 25 §3): after the server refused a large scene
// with 413 (building its mesh raised the server's resident set), a small job's peak_memory_mb is the
// job process's alone, below the server's peak. getrusage's ru_maxrss, which Linux carries across the
// job process's exec, reported the server's peak instead.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "tests/server/live_server.hpp"

namespace stoss::test {
namespace {

/// VmHWM of process `pid` in MB (10^6 bytes).
double peak_mb(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) * 1024.0 / 1e6;
  return 0;
}

TEST(PeakMemory, AJobAfterA413ReportsItsOwnPeakNotTheServers) {
  TempDir dir;
  LiveServer server(dir.path() / "data");
  auto c = server.client();
  const double before = peak_mb(server.pid());
  // An inline mesh of 1.2 million nodes (a 10 MB body, under --max-body-bytes): parsed, then refused for
  // max_nodes.
  nlohmann::json large = box_scene(2, 10);
  large["bodies"][0]["mesh"] = {{"nodes", nlohmann::json::array()}, {"hex8", {{0, 1, 2, 3, 4, 5, 6, 7}}}};
  for (int k = 0; k < 1'200'000; ++k) large["bodies"][0]["mesh"]["nodes"].push_back({0, 0, 0});
  auto refused = c.Post("/v1/jobs", large.dump(), "application/json");
  ASSERT_TRUE(refused);
  ASSERT_EQ(refused->status, 413) << refused->body;
  const double server_peak = peak_mb(server.pid());
  const std::string id = body_json(submit(c, box_scene(2, 10)))["id"];
  const auto done = wait_for_status(c, id, {"succeeded", "failed"});
  ASSERT_EQ(done["status"], "succeeded") << done.dump();
  const double job_peak = done["summary"]["peak_memory_mb"].get<double>();
  std::printf("server %.1f MB before the 413, %.1f MB after; the job %.1f MB\n", before, server_peak,
              job_peak);
  ASSERT_GT(server_peak, before + 20)
      << "the refused scene must raise the server's peak for this test to tell";
  EXPECT_GT(job_peak, 0.0);
  EXPECT_LT(job_peak, server_peak - 10) << "the job reports the server's peak";
}

}  // namespace
}  // namespace stoss::test
