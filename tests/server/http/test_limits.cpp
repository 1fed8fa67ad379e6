// The server limits of a scene: the system shall name every exceeded limit, and refuse a huge generated
// mesh before building it.
#include <gtest/gtest.h>

#include "server/http/limits.hpp"

namespace stoss::server {
namespace {

TEST(Limits, NameEveryExceededLimit) {
  scene::Summary s;
  s.nodes = 300;
  s.steps = 5000;
  s.frames = 10;
  http::Limits limits;
  limits.max_nodes = 100;
  limits.max_steps = 1000;
  auto problem = http::check_scene_limits(s, limits);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->status, 413);
  const nlohmann::json j = problem->to_json();
  ASSERT_EQ(j["limits"].size(), 2u);
  EXPECT_EQ(j["limits"][0], (nlohmann::json{{"name", "max_nodes"}, {"limit", 100}, {"value", 300}}));
  EXPECT_EQ(j["limits"][1]["name"], "max_steps");
  EXPECT_EQ(
      j["detail"],
      "the scene has 300 nodes, more than the server limit max_nodes = 100; the scene has 5000 time steps, "
      "more than the server limit max_steps = 1000");
  s.nodes = 100;
  s.steps = 1000;
  EXPECT_FALSE(http::check_scene_limits(s, limits));
}

TEST(Limits, RefuseAHugeGeneratedMeshBeforeBuildingIt) {
  nlohmann::json scene = {{"bodies", {{{"mesh", {{"box", {{"divisions", {1000, 1000, 1000}}}}}}}}},
                          {"time", {{"step", 0.01}, {"end", 1}}}};
  auto problem = http::check_scene_limits_early(scene, http::Limits{});
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->to_json()["limits"][0]["name"], "max_nodes");
  scene["bodies"][0]["mesh"]["box"]["divisions"] = {10, 10, 10};
  EXPECT_FALSE(http::check_scene_limits_early(scene, http::Limits{}));
  scene["time"]["end"] = 1e9;
  EXPECT_EQ(http::check_scene_limits_early(scene, http::Limits{})->to_json()["limits"][0]["name"],
            "max_steps");
}

}  // namespace
}  // namespace stoss::server
