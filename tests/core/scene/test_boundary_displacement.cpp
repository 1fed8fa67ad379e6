// Requirements for `boundary[i].displacement` and its `amplitude` (docs/scene.md "boundary", issue 23 §2):
// the entry reaches the model, the effect prescribed_motion is named only when a displacement is non-zero,
// and every bad input is one issue at the entry's JSON pointer naming the rule.
#include <gtest/gtest.h>

#include <limits>

#include "core/scene/scene.hpp"
#include "tests/core/scene/scene_issues.hpp"

namespace stoss::scene {
namespace {

using nlohmann::json;

json block_with(json boundary) {
  json scene = json::parse(R"({
    "format": "stoss-scene/1", "name": "pulled block",
    "bodies": [ { "name": "block",
                  "mesh": { "box": { "min": [0, 0, 0], "max": [1, 1, 1], "divisions": [1, 1, 1] } },
                  "material": { "youngs_modulus": 100, "poisson_ratio": 0.3, "density": 1 } } ],
    "time": { "scheme": "energy_momentum", "step": 0.01, "end": 0.1 } })");
  scene["boundary"] = std::move(boundary);
  return scene;
}

using testing::issues_of;

TEST(BoundaryDisplacement, ReachesTheModelWithItsEffect) {
  const model::Model m = load(block_with(json::parse(R"([
    { "surface": "block/bottom" },
    { "surface": "block/top", "fix": "z", "displacement": [0, 0, 0.1], "amplitude": [[0, 0], [1, 1]] } ])")));
  ASSERT_EQ(m.boundary.size(), 2u);
  EXPECT_FALSE(m.boundary[0].moves());
  EXPECT_EQ(m.boundary[1].displacement, Eigen::Vector3d(0, 0, 0.1));
  EXPECT_EQ(m.boundary[1].amplitude.size(), 2u);
  EXPECT_TRUE(m.has_effect(model::effect::prescribed_motion));
  EXPECT_TRUE(m.has_effect(model::effect::dirichlet));
}

TEST(BoundaryDisplacement, AZeroDisplacementIsASupportWithoutTheEffect) {
  const model::Model m =
      load(block_with(json::parse(R"([{ "surface": "block/bottom", "displacement": [0, 0, 0] }])")));
  EXPECT_FALSE(m.boundary[0].moves());
  EXPECT_FALSE(m.has_effect(model::effect::prescribed_motion)) << "only when some displacement is non-zero";
}

struct BadEntry {
  const char* rule;
  const char* entry;
  std::string pointer, message_part;
};

void PrintTo(const BadEntry& b, std::ostream* os) {
  *os << b.rule;
}

class BoundaryDisplacementRule : public ::testing::TestWithParam<BadEntry> {};

TEST_P(BoundaryDisplacementRule, IsOneIssueAtTheEntrysPointer) {
  const BadEntry& b = GetParam();
  json entry = json::parse(b.entry);  // JSON text has no infinity: 1e300 in an entry stands for one
  const auto to_infinity = [](auto& self, json& j) -> void {
    if (j.is_number() && j.get<double>() == 1e300) j = std::numeric_limits<double>::infinity();
    if (j.is_structured())
      for (json& child : j) self(self, child);
  };
  to_infinity(to_infinity, entry);
  const std::vector<Issue> issues = issues_of(block_with(json::array({entry})));
  ASSERT_EQ(issues.size(), 1u) << (issues.empty() ? "none" : issues[0].pointer + ": " + issues[0].message);
  EXPECT_EQ(issues[0].pointer, b.pointer);
  EXPECT_NE(issues[0].message.find(b.message_part), std::string::npos) << issues[0].message;
}

// clang-format off
INSTANTIATE_TEST_SUITE_P(Rules, BoundaryDisplacementRule, ::testing::Values(
  BadEntry{"non-finite component", R"({ "surface": "block/top", "displacement": [0, 1e300, 0] })",
           "/boundary/0/displacement/1", "must be a finite number"},
  BadEntry{"three numbers", R"({ "surface": "block/top", "displacement": [0, 1] })",
           "/boundary/0/displacement", "must be an array of 3 numbers"},
  BadEntry{"direction not held", R"({ "surface": "block/top", "fix": "z", "displacement": [0.1, 0, 0.2] })",
           "/boundary/0/displacement/0", "fix does not hold direction x"},
  BadEntry{"amplitude times increasing",
           R"({ "surface": "block/top", "displacement": [0, 0, 1], "amplitude": [[0, 0], [1, 1], [0.5, 2]] })",
           "/boundary/0/amplitude/2/0", "increasing"},
  BadEntry{"amplitude times finite",
           R"({ "surface": "block/top", "displacement": [0, 0, 1], "amplitude": [[0, 0], [1e300, 1]] })",
           "/boundary/0/amplitude/1/0", "finite"},
  BadEntry{"a(0) = 0", R"({ "surface": "block/top", "displacement": [0, 0, 1], "amplitude": [[0, 0.5], [1, 1]] })",
           "/boundary/0/amplitude", "a(0)"},
  BadEntry{"unknown field", R"({ "surface": "block/top", "velocity": [0, 0, 1] })", "/boundary/0/velocity",
           "unknown field"}));
// clang-format on

}  // namespace
}  // namespace stoss::scene
