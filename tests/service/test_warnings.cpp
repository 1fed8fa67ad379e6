// Checks before the run through the API (docs/api.md): POST /v1/validate and the job JSON carry the
// scene's warnings as {code, pointer, message} and the resolved choices; a job's first ETA is the
// run-time estimate until the run measures one.
#include <gtest/gtest.h>

#include <fstream>

#include "tests/server/live_server.hpp"

namespace stoss::test {
namespace {

nlohmann::json seed_with_master(const std::string& master) {
  std::ifstream in(std::string(STOSS_SOURCE_DIR) + "/api/examples/hollow_ball_plate.json");
  nlohmann::json scene = nlohmann::json::parse(in);
  scene["contact"][0]["master"] = master;
  return scene;
}

const nlohmann::json behind_warning = {
    {"code", "contact_behind_master"},
    {"pointer", "/contact/0/master"},
    {"message",
     "every node of ball/outer is behind plate/bottom (its normals point away); did you mean plate/top?"}};

TEST(WarningsApi, ValidateAnswersWarningsChoicesAndEstimates) {
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "0"});
  auto c = server.client();
  const auto wrong = c.Post("/v1/validate", seed_with_master("plate/bottom").dump(), "application/json");
  ASSERT_TRUE(wrong);
  ASSERT_EQ(wrong->status, 200) << wrong->body;  // a warning never makes a scene invalid
  const auto body = nlohmann::json::parse(wrong->body);
  EXPECT_EQ(body["warnings"], nlohmann::json::array({behind_warning}));
  EXPECT_EQ(body["choices"][0], (nlohmann::json{{"pointer", "/contact/0/master_surface"},
                                                {"value", "smooth"},
                                                {"reason",
                                                 "plate/bottom qualifies for the smooth surface, the "
                                                 "default wherever it can be had"}}));
  EXPECT_GT(body["estimates"]["wall_seconds"].get<double>(), 0);
  EXPECT_EQ(body["estimates"]["bodies"][1]["name"], "plate");

  const auto right = c.Post("/v1/validate", seed_with_master("plate/top").dump(), "application/json");
  ASSERT_TRUE(right);
  EXPECT_EQ(nlohmann::json::parse(right->body)["warnings"], nlohmann::json::array());
}

TEST(WarningsApi, TheJobJsonKeepsTheWarningsAndStartsWithTheEstimatedEta) {
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "0"});  // the job stays queued
  auto c = server.client();
  const nlohmann::json scene = seed_with_master("plate/bottom");
  const auto validated = c.Post("/v1/validate", scene.dump(), "application/json");
  ASSERT_TRUE(validated);
  const double estimate = nlohmann::json::parse(validated->body)["estimates"]["wall_seconds"];
  const auto r = submit(c, scene);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;
  const auto created = nlohmann::json::parse(r->body);
  EXPECT_EQ(created["warnings"], nlohmann::json::array({behind_warning}));
  EXPECT_EQ(created["choices"].size(), 2u);
  EXPECT_DOUBLE_EQ(created["progress"]["eta_seconds"].get<double>(), estimate);
  const auto got = job(c, created["id"]);
  EXPECT_EQ(got["warnings"], created["warnings"]);
  EXPECT_DOUBLE_EQ(got["progress"]["eta_seconds"].get<double>(), estimate);
  const auto listed = c.Get("/v1/jobs");
  ASSERT_TRUE(listed);
  EXPECT_EQ(nlohmann::json::parse(listed->body)["jobs"][0]["warnings"], created["warnings"]);
}

TEST(WarningsCli, ValidatePrintsTheWarningAndStillExits0) {
  TempDir dir;
  const auto path = dir.path() / "bottom.json";
  std::ofstream(path) << seed_with_master("plate/bottom").dump();
  const CommandResult text = run_stoss({"validate", path.string()});
  EXPECT_EQ(text.exit_code, 0) << text.out;
  EXPECT_NE(text.out.find(
                "1 warning:\n  warning contact_behind_master: /contact/0/master: every node of ball/outer "
                "is behind plate/bottom (its normals point away); did you mean plate/top?"),
            std::string::npos)
      << text.out;
  EXPECT_NE(text.out.find("/contact/0/master_surface: smooth ("), std::string::npos) << text.out;
  const CommandResult json = run_stoss({"validate", path.string(), "--json"});
  EXPECT_EQ(json.exit_code, 0) << json.out;
  EXPECT_EQ(nlohmann::json::parse(json.out)["warnings"], nlohmann::json::array({behind_warning}));
}

}  // namespace
}  // namespace stoss::test
