// Each contact pair's master surface shall resolve to "smooth" by default where it is implemented and
// the master qualifies, to "faceted" otherwise, and an explicit "smooth" that cannot be had shall be
// refused at validation with its JSON pointer and the reason (docs/smooth_master_surface.md §1).
#include <gtest/gtest.h>

#include "core/scene/scene.hpp"

namespace stoss::scene {
namespace {

using nlohmann::json;

const json material = {{"youngs_modulus", 1e4}, {"poisson_ratio", 0.4}, {"density", 1}};

/// A ball over a plate; contact pair 0 with the given master.
json ball_and_plate(const std::string& master) {
  return {{"format", "stoss-scene/1"},
          {"bodies",
           {{{"name", "ball"},
             {"mesh",
              {{"hollow_sphere", {{"center", {0, 0, 1.3}}, {"outer_radius", 1.0}, {"inner_radius", 0.8}}}}},
             {"material", material}},
            {{"name", "plate"},
             {"mesh", {{"box", {{"min", {-2, -2, -0.4}}, {"max", {2, 2, 0}}, {"divisions", {4, 4, 1}}}}}},
             {"material", material}}}},
          {"contact", {{{"slave", master == "ball/outer" ? "plate/top" : "ball/outer"}, {"master", master}}}},
          {"time", {{"step", 0.01}, {"end", 1.0}}}};
}

/// One hexahedron given inline, its six faces as the surface "all" (outward node order).
json one_cube() {
  return {
      {"name", "cube"},
      {"mesh",
       {{"nodes",
         {{-2, -2, -1},
          {2, -2, -1},
          {2, 2, -1},
          {-2, 2, -1},
          {-2, -2, 0},
          {2, -2, 0},
          {2, 2, 0},
          {-2, 2, 0}}},
        {"hex8", {{0, 1, 2, 3, 4, 5, 6, 7}}},
        {"surfaces",
         {{"all", {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}}}}}},
      {"material", material}};
}

std::string refusal(const json& scene) {
  try {
    load(scene);
  } catch (const SceneError& e) {
    return e.issues.at(0).pointer + ": " + e.issues.at(0).message;
  }
  return "accepted";
}

TEST(MasterSurface, DefaultsToSmoothWithKeptGapOnAPlate) {
  const model::Model m = load(ball_and_plate("plate/top"));
  EXPECT_EQ(m.contact.at(0).master_surface, model::MasterSurface::smooth);
  EXPECT_EQ(m.contact.at(0).switch_gap, model::SwitchGap::keep);
  EXPECT_EQ(m.scene["contact"][0]["master_surface"], "smooth");
  EXPECT_EQ(m.scene["contact"][0]["switch_gap"], "keep");
}

TEST(MasterSurface, EveryLagrangeSchemeDefaultsToSmooth) {
  for (const char* scheme : {"energy_momentum", "midpoint", "hht"}) {
    json scene = ball_and_plate("plate/top");
    scene["time"]["scheme"] = scheme;
    EXPECT_EQ(load(scene).contact.at(0).master_surface, model::MasterSurface::smooth) << scheme;
  }
}

TEST(MasterSurface, PenaltyPairsAreSmoothByDefaultWithTheKeepRule) {
  json penalty = ball_and_plate("plate/top");
  penalty["contact"][0]["enforcement"] = "penalty";
  penalty["contact"][0]["friction"] = 0.2;
  const model::Model m = load(penalty);
  EXPECT_EQ(m.scene["contact"][0]["master_surface"], "smooth");
  EXPECT_EQ(m.contact.at(0).switch_gap, model::SwitchGap::keep);
}

TEST(MasterSurface, DefaultsToFacetedWhereTheMasterDoesNotQualify) {
  json cube = ball_and_plate("plate/top");
  cube["bodies"][1] = one_cube();
  cube["contact"][0]["master"] = "cube/all";  // every corner of every face extraordinary
  EXPECT_EQ(load(cube).contact.at(0).master_surface, model::MasterSurface::faceted);
}

TEST(MasterSurface, ASphereWithExtraordinaryCornersIsSmoothByDefault) {
  const model::Model sphere = load(ball_and_plate("ball/outer"));  // cube corners: valence 3 (§2.5)
  EXPECT_EQ(sphere.contact.at(0).master_surface, model::MasterSurface::smooth);
}

TEST(MasterSurface, ExplicitSmoothThatCannotBeHadIsRefusedWithItsPointer) {
  json cube = ball_and_plate("plate/top");
  cube["bodies"][1] = one_cube();
  cube["contact"][0]["master"] = "cube/all";
  cube["contact"][0]["master_surface"] = "smooth";
  const std::string why = refusal(cube);
  EXPECT_EQ(why.rfind("/contact/0/master_surface: master cube/all cannot carry a smooth surface: face ", 0),
            0u)
      << why;
  EXPECT_NE(why.find("has extraordinary vertices at nodes"), std::string::npos) << why;
}

TEST(MasterSurface, AMortarPairResolvesToFacetedAndTheChoiceSaysWhy) {
  json scene = ball_and_plate("plate/top");  // a master that qualifies for the smooth surface
  scene["contact"][0]["discretization"] = "mortar";
  const model::Model m = load(scene);
  EXPECT_EQ(m.contact.at(0).discretization, model::Discretization::mortar);
  EXPECT_EQ(m.contact.at(0).master_surface, model::MasterSurface::faceted);
  EXPECT_EQ(m.scene["contact"][0]["master_surface"], "faceted") << "the resolved scene says so";
  EXPECT_EQ(m.scene["contact"][0]["discretization"], "mortar");
  const Summary s = summarize(m);
  ASSERT_GE(s.choices.size(), 1u);
  EXPECT_EQ(s.choices[0].pointer, "/contact/0/master_surface");
  EXPECT_EQ(s.choices[0].value, "faceted");
  EXPECT_NE(s.choices[0].reason.find("discretization \"mortar\" integrates on the faceted surface"),
            std::string::npos)
      << s.choices[0].reason;
  EXPECT_EQ(load(m.scene).contact.at(0).master_surface, model::MasterSurface::faceted)
      << "the resolved scene loads as it is";
  ASSERT_GE(s.choices.size(), 2u);
  EXPECT_EQ(s.choices[1].pointer, "/contact/0/switch_gap");
  EXPECT_EQ(s.choices[1].reason, "unused: a node-to-segment setting, and a mortar pair has no face switches");
}

TEST(MasterSurface, UnknownValueIsRefusedWithTheChoices) {
  json scene = ball_and_plate("plate/top");
  scene["contact"][0]["master_surface"] = "nurbs";
  const std::string why = refusal(scene);
  EXPECT_EQ(why.rfind("/contact/0/master_surface: ", 0), 0u) << why;
  EXPECT_NE(why.find("smooth"), std::string::npos) << why;
  EXPECT_NE(why.find("nurbs"), std::string::npos) << why;
}

TEST(MasterSurface, ExplicitFacetedIsKeptWithTheClampRule) {
  json scene = ball_and_plate("plate/top");
  scene["contact"][0]["master_surface"] = "faceted";
  const model::Model m = load(scene);
  EXPECT_EQ(m.contact.at(0).master_surface, model::MasterSurface::faceted);
  EXPECT_EQ(m.contact.at(0).switch_gap, model::SwitchGap::clamp);
}

// A pair that the contact module cannot run is refused at validation, not in the worker.
TEST(ContactScheme, PenaltyWithHhtIsRefusedAtValidation) {
  json scene = ball_and_plate("plate/top");
  scene["time"]["scheme"] = "hht";
  scene["contact"][0]["enforcement"] = "penalty";
  EXPECT_EQ(refusal(scene),
            "/contact/0/enforcement: \"penalty\" is not implemented with time.scheme \"hht\"; use "
            "energy_momentum or midpoint");
}

// Every body has its whole boundary as the surface "boundary"; as a master it is one smooth surface
// across the edges between the named surfaces (a box: top, xmax, … joined, corners extraordinary).
TEST(MasterSurface, ABoxsWholeBoundaryIsOneSmoothMaster) {
  json scene = ball_and_plate("plate/boundary");
  scene["bodies"][1]["mesh"]["box"]["divisions"] = {4, 4, 2};  // ≤ 1 extraordinary corner per face
  const model::Model m = load(scene);
  EXPECT_EQ(m.contact.at(0).master_surface, model::MasterSurface::smooth);
  EXPECT_EQ(m.mesh.surface("plate/boundary").size(), 2u * (16 + 8 + 8));
}

}  // namespace
}  // namespace stoss::scene
