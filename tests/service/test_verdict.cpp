// The system shall keep a suspect run's results and say so (issue 25 §1, docs/results.md "Verdict"):
// a job whose run breaks a check ends `succeeded` with summary.verdict "suspect" and the failed check
// in summary.checks, and GET /v1/jobs?verdict=suspect lists it and not an ok job.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "tests/server/live_server.hpp"

namespace stoss::test {
namespace {

/// The tumbling bar, 4 steps, with an iteration cap of 10: the Newton bound is 0.6 · 10 = 6 iterations
/// per step and the bar takes 7.
nlohmann::json suspect_scene() {
  nlohmann::json scene =
      nlohmann::json::parse(std::ifstream(std::string(STOSS_SOURCE_DIR) + "/api/examples/tumbling_bar.json"));
  scene["time"]["end"] = 0.2;
  scene["solver"]["max_iterations"] = 10;
  return scene;
}

std::vector<std::string> listed_ids(httplib::Client& c, const std::string& query) {
  std::vector<std::string> ids;
  const nlohmann::json body = body_json(c.Get("/v1/jobs?" + query));
  for (const auto& job : body["jobs"]) ids.push_back(job["id"]);
  return ids;
}

bool contains(const std::vector<std::string>& ids, const std::string& id) {
  return std::find(ids.begin(), ids.end(), id) != ids.end();
}

TEST(Verdict, SuspectJobSucceedsWithItsReasonsAndIsListedByVerdict) {
  TempDir dir;
  LiveServer server(dir.path() / "data");
  auto c = server.client();
  const std::string suspect = body_json(submit(c, suspect_scene()))["id"];
  const std::string ok = body_json(submit(c, box_scene(2, 10)))["id"];
  const auto done = wait_for_status(c, suspect, {"succeeded", "failed"});
  ASSERT_EQ(done["status"], "succeeded") << done.dump();
  const auto& summary = done["summary"];
  EXPECT_EQ(summary["verdict"], "suspect") << summary.dump();
  bool newton_failed = false;
  for (const auto& check : summary["checks"]) {
    EXPECT_TRUE(check.contains("value") && check.contains("bound")) << check.dump();
    if (check["name"] == "newton_iterations_per_step") newton_failed = !check["passed"].get<bool>();
  }
  EXPECT_TRUE(newton_failed) << summary.dump();
  const auto ok_done = wait_for_status(c, ok, {"succeeded", "failed"});
  ASSERT_EQ(ok_done["status"], "succeeded") << ok_done.dump();
  EXPECT_EQ(ok_done["summary"]["verdict"], "ok") << ok_done["summary"].dump();

  const std::vector<std::string> suspects = listed_ids(c, "verdict=suspect&limit=200");
  EXPECT_TRUE(contains(suspects, suspect));
  EXPECT_FALSE(contains(suspects, ok));
  EXPECT_TRUE(contains(listed_ids(c, "verdict=ok&limit=200"), ok));
  auto bad = c.Get("/v1/jobs?verdict=maybe");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  EXPECT_NE(bad->body.find("verdict must be one of ok, suspect"), std::string::npos) << bad->body;
}

}  // namespace
}  // namespace stoss::test
