// Requirements for `time.scheme: "static"` in scenes (docs/scene.md "Time", issue 23 §3; docs/theory.md
// §5b.6, §5b.8): the scheme is selectable and reported as the effect `static` in place of `inertia`; a body
// that nothing holds is refused at /bodies/i naming the body and its free rigid modes; `time.tolerance`,
// moving bodies and impact treatments other than "exact" are refused at their pointers with the rule named.
#include <gtest/gtest.h>

#include "core/scene/scene.hpp"
#include "tests/core/scene/scene_issues.hpp"

namespace stoss::scene {
namespace {

using nlohmann::json;
using testing::issues_of;

const json material = {{"youngs_modulus", 1000}, {"poisson_ratio", 0.3}, {"density", 1}};

json box_body(const std::string& name, double z0) {
  return {{"name", name},
          {"mesh", {{"box", {{"min", {0, 0, z0}}, {"max", {1, 1, z0 + 0.5}}, {"divisions", {2, 2, 1}}}}}},
          {"material", material}};
}

/// One block with `boundary`, static steps.
json static_block(const json& boundary) {
  return {{"format", "stoss-scene/1"},
          {"bodies", {box_body("block", 0)}},
          {"boundary", boundary},
          {"gravity", {0, 0, -10}},
          {"time", {{"scheme", "static"}, {"step", 0.5}, {"end", 1}}}};
}

/// `upper` resting on `lower` (bottom held), the pair upper/bottom → lower/top; `upper_boundary` added.
json stacked(const json& upper_boundary) {
  json scene = static_block(json::array({{{"surface", "lower/bottom"}}}));
  scene["bodies"] = {box_body("lower", 0), box_body("upper", 0.5)};
  for (const json& e : upper_boundary) scene["boundary"].push_back(e);
  scene["contact"] = json::array({{{"slave", "upper/bottom"}, {"master", "lower/top"}}});
  return scene;
}

std::string text(const std::vector<Issue>& issues) {
  std::string out;
  for (const Issue& i : issues) out += i.pointer + ": " + i.message + "\n";
  return out.empty() ? "none" : out;
}

TEST(StaticScene, TheSchemeIsSelectableAndReportedAsTheEffectStaticInPlaceOfInertia) {
  const model::Model m = load(static_block(json::array({{{"surface", "block/bottom"}}})));
  EXPECT_EQ(m.time.scheme, model::Scheme::equilibrium);
  EXPECT_EQ(model::to_string(m.time.scheme), "static");
  EXPECT_EQ(m.effects, (std::vector<std::string>{"static", "elasticity", "gravity", "dirichlet"}));
  EXPECT_EQ(m.scene["time"]["scheme"], "static");
  json dynamic = static_block(json::array({{{"surface", "block/bottom"}}}));
  dynamic["time"]["scheme"] = "energy_momentum";
  EXPECT_FALSE(load(dynamic).has_effect(model::effect::static_steps)) << "only when asked for";
}

TEST(StaticScene, AnUnknownSchemeNamesStaticAmongTheChoices) {
  json scene = static_block(json::array({{{"surface", "block/bottom"}}}));
  scene["time"]["scheme"] = "quasi_static";
  const auto issues = issues_of(scene);
  ASSERT_EQ(issues.size(), 1u) << text(issues);
  EXPECT_EQ(issues[0].pointer, "/time/scheme");
  EXPECT_NE(issues[0].message.find("generalized_alpha, static"), std::string::npos) << issues[0].message;
}

TEST(StaticScene, ATimeToleranceIsRefusedAtItsPointer) {
  json scene = static_block(json::array({{{"surface", "block/bottom"}}}));
  scene["time"]["tolerance"] = 1e-4;
  const auto issues = issues_of(scene);
  ASSERT_EQ(issues.size(), 1u) << text(issues);
  EXPECT_EQ(issues[0].pointer, "/time/tolerance");
  EXPECT_NE(issues[0].message.find("is not allowed with scheme \"static\""), std::string::npos)
      << issues[0].message;
}

TEST(StaticScene, ABodyNothingHoldsIsRefusedNamingItAndEverySixFreeModes) {
  const auto issues = issues_of(static_block(json::array()));
  ASSERT_EQ(issues.size(), 1u) << text(issues);
  EXPECT_EQ(issues[0].pointer, "/bodies/0");
  const std::string& m = issues[0].message;
  EXPECT_NE(m.find("body 'block' is free to move as a rigid body"), std::string::npos) << m;
  for (const char* mode :
       {"translation along x", "translation along y", "translation along z",
        "rotation about x through (0.5, 0.5, 0.25)", "rotation about y", "rotation about z"})
    EXPECT_NE(m.find(mode), std::string::npos) << mode << " in: " << m;
}

TEST(StaticScene, ABodyOnOneRollerIsRefusedNamingTheThreeModesTheRollerLeaves) {
  const auto issues = issues_of(static_block(json::array({{{"surface", "block/bottom"}, {"fix", "z"}}})));
  ASSERT_EQ(issues.size(), 1u) << text(issues);
  const std::string& m = issues[0].message;
  for (const char* mode : {"translation along x", "translation along y", "rotation about z"})
    EXPECT_NE(m.find(mode), std::string::npos) << mode << " in: " << m;
  EXPECT_EQ(m.find("translation along z"), std::string::npos) << m;
  EXPECT_EQ(m.find("rotation about x"), std::string::npos) << m;
}

TEST(StaticScene, ABodyHeldThroughAContactWithAHeldBodyNeedsRollersForItsTangentialModes) {
  const json rollers =
      json::array({{{"surface", "upper/xmin"}, {"fix", "x"}}, {{"surface", "upper/ymin"}, {"fix", "y"}}});
  EXPECT_EQ(text(issues_of(stacked(rollers))), "none") << "contact holds the normal, the rollers the rest";
  const auto issues = issues_of(stacked(json::array()));
  ASSERT_EQ(issues.size(), 1u) << text(issues);
  EXPECT_EQ(issues[0].pointer, "/bodies/1");
  EXPECT_NE(issues[0].message.find("body 'upper'"), std::string::npos) << issues[0].message;
  EXPECT_NE(issues[0].message.find("translation along x"), std::string::npos) << issues[0].message;
}

TEST(StaticScene, AContactHoldsOnlyWhereItsSurfacesTouchAtTheStart) {
  const json rollers =
      json::array({{{"surface", "upper/xmin"}, {"fix", "x"}}, {{"surface", "upper/ymin"}, {"fix", "y"}}});
  json apart = stacked(rollers);
  apart["bodies"][1]["mesh"]["box"]["min"] = {0, 0, 0.51};  // 0.01 above the lower block: nothing holds z
  apart["bodies"][1]["mesh"]["box"]["max"] = {1, 1, 1.01};
  const auto issues = issues_of(apart);
  ASSERT_EQ(issues.size(), 1u) << text(issues);
  EXPECT_EQ(issues[0].pointer, "/bodies/1");
  EXPECT_NE(issues[0].message.find("(translation along z)"), std::string::npos) << issues[0].message;
}

TEST(StaticScene, PrescribedMotionHoldsABody) {
  const json pulled = json::array({{{"surface", "block/bottom"}, {"displacement", {0.1, 0, 0}}}});
  EXPECT_EQ(text(issues_of(static_block(pulled))), "none");
}

TEST(StaticScene, LagrangePairsCloseTheirGapByDefaultAndRefuseImpactTreatments) {
  const json rollers =
      json::array({{{"surface", "upper/xmin"}, {"fix", "x"}}, {{"surface", "upper/ymin"}, {"fix", "y"}}});
  EXPECT_EQ(load(stacked(rollers)).contact.at(0).impact, model::ImpactMode::exact);
  json persist = stacked(rollers);
  persist["contact"][0]["impact"] = "persist";
  const auto issues = issues_of(persist);
  ASSERT_EQ(issues.size(), 1u) << text(issues);
  EXPECT_EQ(issues[0].pointer, "/contact/0/impact");
  EXPECT_NE(issues[0].message.find("must be \"exact\" with time.scheme \"static\""), std::string::npos)
      << issues[0].message;
}

TEST(StaticScene, AnInitialVelocityIsRefusedAtItsPointer) {
  json scene = static_block(json::array({{{"surface", "block/bottom"}}}));
  scene["bodies"][0]["initial_angular_velocity"] = {0, 0, 1};
  const auto issues = issues_of(scene);
  ASSERT_EQ(issues.size(), 1u) << text(issues);
  EXPECT_EQ(issues[0].pointer, "/bodies/0/initial_angular_velocity");
  EXPECT_NE(issues[0].message.find("must be [0, 0, 0] with time.scheme \"static\""), std::string::npos)
      << issues[0].message;
}

}  // namespace
}  // namespace stoss::scene
