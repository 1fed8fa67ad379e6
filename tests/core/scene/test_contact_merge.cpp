// No silent seams (docs/scene.md "Pairs that share a slave", issue 23 §5): contact pairs that share a slave
// and whose masters belong to one body become one pair with the union master when their settings agree; the
// resolved scene and the resolved choices of `stoss validate` show the merge; when their settings differ,
// the scene is refused at the later pair, naming both pairs and showing the list form.
#include <gtest/gtest.h>

#include "core/scene/scene.hpp"
#include "core/scene/warnings.hpp"
#include "tests/core/scene/scene_issues.hpp"

namespace stoss::scene {
namespace {

using nlohmann::json;
using testing::issues_of;

const json material = {{"youngs_modulus", 1e4}, {"poisson_ratio", 0.4}, {"density", 1}};

json box(const std::string& name, std::array<double, 3> lo, std::array<double, 3> hi) {
  return {{"name", name},
          {"mesh", {{"box", {{"min", lo}, {"max", hi}, {"divisions", {2, 2, 2}}}}}},
          {"material", material}};
}

/// A box, a block above its top–xmax edge, a plate beside it; `contact` as given.
json edge_scene(const json& contact) {
  return {{"format", "stoss-scene/1"},
          {"bodies",
           {box("box", {0, 0, 0}, {2, 2, 1}), box("block", {1.8, 0.8, 1.1}, {2.2, 1.2, 1.5}),
            box("plate", {3, 0, 0}, {4, 2, 0.2})}},
          {"contact", contact},
          {"time", {{"step", 0.01}, {"end", 0.1}}}};
}

json pair(const std::string& slave, const json& master) {
  return {{"slave", slave}, {"master", master}};
}

std::string text(const std::vector<Issue>& issues) {
  std::string out;
  for (const Issue& i : issues) out += i.pointer + ": " + i.message + "\n";
  return out.empty() ? "none" : out;
}

TEST(ContactMerge, TwoPairsFromOneSlaveToTwoSurfacesOfOneBodyBecomeOnePairWithTheUnionMaster) {
  const model::Model m =
      load(edge_scene(json::array({pair("block/boundary", "box/top"), pair("block/boundary", "box/xmax")})));
  ASSERT_EQ(m.contact.size(), 1u);
  EXPECT_EQ(m.contact[0].master, "box/top+xmax");
  EXPECT_EQ(m.contact[0].master_surface, model::MasterSurface::smooth)
      << "one smooth surface across the edge";
  ASSERT_EQ(m.scene["contact"].size(), 1u) << "the resolved scene shows the merge";
  EXPECT_EQ(m.scene["contact"][0]["master"], json({"box/top", "box/xmax"}));
  ASSERT_EQ(m.merged_contact.size(), 1u);
  EXPECT_EQ(m.merged_contact[0].written, (std::vector<int>{0, 1}));
  const Summary s = summarize(m);
  ASSERT_FALSE(s.choices.empty());
  EXPECT_EQ(s.choices[0].pointer, "/contact/0/master");
  EXPECT_EQ(s.choices[0].value, R"(["box/top","box/xmax"])");
  EXPECT_NE(s.choices[0].reason.find("pairs /contact/0 and /contact/1 as written share slave"),
            std::string::npos)
      << s.choices[0].reason;
  EXPECT_TRUE(s.warnings.empty());
  EXPECT_EQ(load(m.scene).contact.size(), 1u) << "the resolved scene loads as it is";
}

TEST(ContactMerge, PairsToOtherBodiesOrFromOtherSlavesStaySeparateAndTheRestKeepTheirOrder) {
  const model::Model m = load(edge_scene(
      json::array({pair("block/boundary", "box/top"), pair("block/boundary", "plate/top"),
                   pair("block/bottom", "box/xmax"), pair("block/boundary", {"box/xmax", "box/top"})})));
  ASSERT_EQ(m.contact.size(), 3u);
  EXPECT_EQ(m.scene["contact"][0]["master"], json({"box/top", "box/xmax"})) << "each surface once, in order";
  EXPECT_EQ(m.contact[1].master, "plate/top");
  EXPECT_EQ(m.contact[2].slave, "block/bottom");
  ASSERT_EQ(m.merged_contact.size(), 1u);
  EXPECT_EQ(m.merged_contact[0].pair, 0);
  EXPECT_EQ(m.merged_contact[0].written, (std::vector<int>{0, 3}));
}

TEST(ContactMerge, PairsWhoseSettingsDifferAreRefusedNamingBothAndTheListForm) {
  json second = pair("block/boundary", "box/xmax");
  second["switch_hysteresis"] = 0.1;
  const auto issues = issues_of(edge_scene(json::array({pair("block/boundary", "box/top"), second})));
  ASSERT_EQ(issues.size(), 1u) << text(issues);
  EXPECT_EQ(issues[0].pointer, "/contact/1");
  const std::string& m = issues[0].message;
  EXPECT_NE(m.find("shares slave \"block/boundary\" with /contact/0"), std::string::npos) << m;
  EXPECT_NE(m.find("switch_hysteresis 0.1 here, 0.05 there"), std::string::npos) << m;
  EXPECT_NE(m.find(R"("master": ["box/top","box/xmax"])"), std::string::npos) << m;
}

TEST(ContactMerge, ASettingGivenInOnlyOnePairIsADifference) {
  json second = pair("block/boundary", "box/xmax");
  second["master_surface"] = "faceted";
  const auto issues = issues_of(edge_scene(json::array({pair("block/boundary", "box/top"), second})));
  ASSERT_EQ(issues.size(), 1u) << text(issues);
  EXPECT_NE(issues[0].message.find("master_surface \"faceted\" here, not given there"), std::string::npos)
      << issues[0].message;
}

TEST(ContactMerge, TheDiscretizationIsASettingThatMustAgree) {
  json second = pair("block/boundary", "box/xmax");
  second["discretization"] = "mortar";
  const auto issues = issues_of(edge_scene(json::array({pair("block/boundary", "box/top"), second})));
  ASSERT_EQ(issues.size(), 1u) << text(issues);
  EXPECT_EQ(issues[0].pointer, "/contact/1");
  EXPECT_NE(issues[0].message.find(R"(discretization "mortar" here, "node_to_segment" there)"),
            std::string::npos)
      << issues[0].message;
  json first = pair("block/boundary", "box/top");
  first["discretization"] = "mortar";
  const model::Model m = load(edge_scene(json::array({first, second})));
  ASSERT_EQ(m.contact.size(), 1u) << "mortar pairs that agree merge";
  EXPECT_EQ(m.contact[0].discretization, model::Discretization::mortar);
  EXPECT_EQ(m.scene["contact"][0]["master_surface"], "faceted");
}

TEST(ContactMerge, AnErrorAboutALaterPairPointsAtItAsWritten) {
  json scene = edge_scene(json::array({pair("block/boundary", "box/top"), pair("block/boundary", "box/xmax"),
                                       pair("plate/top", "cube/all")}));
  scene["contact"][2]["master_surface"] = "smooth";  // one hexahedron: every corner extraordinary
  scene["bodies"].push_back(
      {{"name", "cube"},
       {"mesh",
        {{"nodes", {{5, 0, 0}, {6, 0, 0}, {6, 1, 0}, {5, 1, 0}, {5, 0, 1}, {6, 0, 1}, {6, 1, 1}, {5, 1, 1}}},
         {"hex8", {{0, 1, 2, 3, 4, 5, 6, 7}}},
         {"surfaces",
          {{"all", {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}}}}}},
       {"material", material}});
  const auto issues = issues_of(scene);
  ASSERT_EQ(issues.size(), 1u) << text(issues);
  EXPECT_EQ(issues[0].pointer, "/contact/2/master_surface") << "the merged list has it at /contact/1";
  EXPECT_NE(issues[0].message.find("master cube/all cannot carry a smooth surface"), std::string::npos)
      << issues[0].message;
}

TEST(ContactMerge, AWarningAboutALaterPairPointsAtItAsWritten) {
  const model::Model m =
      load(edge_scene(json::array({pair("block/boundary", "box/top"), pair("block/boundary", "box/xmax"),
                                   pair("plate/top", "box/top")})));  // the plate lies below the box's top
  const Summary s = summarize(m);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0].code, "contact_behind_master");
  EXPECT_EQ(s.warnings[0].pointer, "/contact/2/master") << "the merged list has it at /contact/1";
}

}  // namespace
}  // namespace stoss::scene
