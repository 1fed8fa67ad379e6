// Requirements for the scene's `loads` (docs/scene.md "loads", issue 23 §1): each entry parses into the model
// with its effect named, and every bad input is one issue at the entry's JSON pointer naming the rule.
#include <gtest/gtest.h>

#include "core/scene/scene.hpp"
#include "tests/core/scene/scene_issues.hpp"

namespace stoss::scene {
namespace {

using nlohmann::json;

json block_with(json loads) {
  json scene = json::parse(R"({
    "format": "stoss-scene/1", "name": "loaded block",
    "bodies": [ { "name": "block",
                  "mesh": { "box": { "min": [0, 0, 0], "max": [1, 1, 1], "divisions": [1, 1, 1] } },
                  "material": { "youngs_modulus": 100, "poisson_ratio": 0.3, "density": 1 } } ],
    "boundary": [ { "surface": "block/bottom" } ],
    "time": { "scheme": "energy_momentum", "step": 0.01, "end": 0.1 } })");
  scene["loads"] = std::move(loads);
  return scene;
}

using testing::issues_of;

TEST(SceneLoads, PressureAndTractionEntriesReachTheModelWithTheirEffects) {
  const model::Model m = load(block_with(json::parse(R"([
    { "surface": "block/top", "pressure": 2.5, "amplitude": [[0, 0], [1, 1]] },
    { "surface": "block/xmax", "traction": [1, 0, -1] } ])")));
  ASSERT_EQ(m.loads.size(), 2u);
  EXPECT_EQ(m.loads[0].kind, model::Load::Kind::pressure);
  EXPECT_EQ(m.loads[0].pressure, 2.5);
  EXPECT_EQ(m.loads[0].amplitude.size(), 2u);
  EXPECT_EQ(m.loads[1].kind, model::Load::Kind::traction);
  EXPECT_EQ(m.loads[1].traction, Eigen::Vector3d(1, 0, -1));
  EXPECT_TRUE(m.loads[1].amplitude.empty());
  EXPECT_TRUE(m.has_effect(model::effect::pressure));
  EXPECT_TRUE(m.has_effect(model::effect::traction));
  EXPECT_FALSE(load(block_with(json::array())).has_effect(model::effect::pressure)) << "only when asked for";
}

struct BadLoad {
  const char* rule;
  const char* entry;
  std::string pointer, message_part;
};

void PrintTo(const BadLoad& b, std::ostream* os) {
  *os << b.rule;
}

class SceneLoadRule : public ::testing::TestWithParam<BadLoad> {};

TEST_P(SceneLoadRule, IsOneIssueAtTheEntrysPointer) {
  const BadLoad& b = GetParam();
  const std::vector<Issue> issues = issues_of(block_with(json::array({json::parse(b.entry)})));
  ASSERT_EQ(issues.size(), 1u) << (issues.empty() ? "none" : issues[0].pointer + ": " + issues[0].message);
  EXPECT_EQ(issues[0].pointer, b.pointer);
  EXPECT_NE(issues[0].message.find(b.message_part), std::string::npos) << issues[0].message;
}

// clang-format off
INSTANTIATE_TEST_SUITE_P(Rules, SceneLoadRule, ::testing::Values(
  BadLoad{"unknown surface", R"({ "surface": "block/lid", "pressure": 1 })", "/loads/0/surface", "lid"},
  BadLoad{"both kinds", R"({ "surface": "block/top", "pressure": 1, "traction": [0, 0, 1] })", "/loads/0",
          R"(must give exactly one of "pressure" and "traction", got both)"},
  BadLoad{"neither kind", R"({ "surface": "block/top" })", "/loads/0",
          R"(must give exactly one of "pressure" and "traction", got neither)"},
  BadLoad{"pressure a number", R"({ "surface": "block/top", "pressure": "high" })", "/loads/0/pressure", "number"},
  BadLoad{"traction a vector", R"({ "surface": "block/top", "traction": [0, 1] })", "/loads/0/traction",
          "must be an array of 3 numbers"},
  BadLoad{"amplitude pairs", R"({ "surface": "block/top", "pressure": 1, "amplitude": [[0, 0], [1]] })",
          "/loads/0/amplitude/1", "must be a pair [time, factor] of numbers"},
  BadLoad{"amplitude times increasing", R"({ "surface": "block/top", "pressure": 1, "amplitude": [[0, 0], [1, 1], [1, 2]] })",
          "/loads/0/amplitude/2/0", "increasing"},
  BadLoad{"unknown field", R"({ "surface": "block/top", "pressure": 1, "phase": 0 })", "/loads/0/phase", "unknown field"}));
// clang-format on

}  // namespace
}  // namespace stoss::scene
