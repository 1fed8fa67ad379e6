// Pairs that share a slave are merged where the service shows the resolved scene (issue 23 §5; docs/scene.md
// "Pairs that share a slave"): /v1/validate lists the merge among the resolved choices, and a job's scene,
// GET /v1/jobs/{id}/scene?resolved=true, holds the one pair with the union master that the worker runs.
#include <gtest/gtest.h>

#include <fstream>

#include "tests/server/live_server.hpp"

namespace stoss::test {
namespace {

nlohmann::json ball_on_box_edge() {
  std::ifstream in(std::string(STOSS_SOURCE_DIR) + "/api/examples/ball_on_box_edge.json");
  return nlohmann::json::parse(in);
}

const nlohmann::json union_master = {"box/top", "box/xmax"};

TEST(ResolvedScene, ValidateNamesTheMergeOfTwoPairsSharingASlave) {
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "0"});
  auto c = server.client();
  const nlohmann::json scene = ball_on_box_edge();
  ASSERT_EQ(scene["contact"].size(), 2u) << "the example is written as two pairs";
  const auto r = c.Post("/v1/validate", scene.dump(), "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const nlohmann::json choice = nlohmann::json::parse(r->body)["choices"][0];
  EXPECT_EQ(choice["pointer"], "/contact/0/master");
  // A choice's value is text (docs/api.md, "Validate"); for a list master, the list written as JSON.
  EXPECT_EQ(nlohmann::json::parse(choice["value"].get<std::string>()), union_master);
  const std::string reason = choice["reason"];
  EXPECT_NE(reason.find("pairs /contact/0 and /contact/1 as written share slave \"ball/outer\""),
            std::string::npos)
      << reason;
}

TEST(ResolvedScene, AJobsResolvedSceneHoldsOnePairWithTheUnionMaster) {
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "0"});  // the job stays queued: the scene is what runs
  auto c = server.client();
  const auto created = submit(c, ball_on_box_edge());
  ASSERT_TRUE(created);
  ASSERT_EQ(created->status, 201) << created->body;
  const std::string id = nlohmann::json::parse(created->body)["id"];
  for (const char* query : {"?resolved=true", ""}) {
    const auto r = c.Get(("/v1/jobs/" + id + "/scene" + query).c_str());
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 200) << r->body;
    const nlohmann::json contact = nlohmann::json::parse(r->body)["contact"];
    ASSERT_EQ(contact.size(), 1u) << query << ": " << contact.dump();
    EXPECT_EQ(contact[0]["slave"], "ball/outer");
    EXPECT_EQ(contact[0]["master"], union_master) << query;
  }
}

}  // namespace
}  // namespace stoss::test
