// Checks before the run (docs/scene.md, "Checks before the run"): each warning fires on the mistake it
// is for, with its code, JSON pointer and fix; the shipped examples raise none; the estimates match the
// formulas (W1)–(W6) on scenes whose numbers are known by hand; unknown fields say what was meant.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/scene/scene.hpp"
#include "core/scene/spelling.hpp"
#include "core/scene/warnings.hpp"

namespace stoss::scene {
namespace {

using nlohmann::json;

const std::string examples = std::string(STOSS_SOURCE_DIR) + "/api/examples/";

json seed() {
  std::ifstream in(examples + "hollow_ball_plate.json");
  return json::parse(in);
}

Summary summary_of(const json& scene) {
  return summarize(load(scene));
}

std::vector<Warning> with_code(const Summary& s, const std::string& code) {
  std::vector<Warning> out;
  for (const Warning& w : s.warnings)
    if (w.code == code) out.push_back(w);
  return out;
}

TEST(Warnings, NoShippedExampleRaisesAny) {
  int examples_seen = 0;
  for (const auto& entry : std::filesystem::directory_iterator(examples)) {
    if (entry.path().extension() != ".json") continue;
    ++examples_seen;
    const Summary s = summarize(load_file(entry.path().string()));
    for (const Warning& w : s.warnings)
      ADD_FAILURE() << entry.path() << ": " << w.code << " " << w.pointer << " " << w.message;
    EXPECT_GT(s.estimates.wall_seconds, 0) << entry.path();
  }
  EXPECT_GE(examples_seen, 10);
}

TEST(Warnings, ASlaveBehindItsMasterNamesTheSurfaceItFaces) {
  json scene = seed();
  scene["contact"][0]["master"] = "plate/bottom";
  const Summary s = summary_of(scene);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0].code, warning::contact_behind_master);
  EXPECT_EQ(s.warnings[0].pointer, "/contact/0/master");
  EXPECT_EQ(
      s.warnings[0].message,
      "every node of ball/outer is behind plate/bottom (its normals point away); did you mean plate/top?");
}

TEST(Warnings, ABlockPressedSlightlyIntoItsMasterIsNotBehindIt) {
  json scene = seed();
  // Its bottom 1e-3 below plate/top, whose faces are 0.25 wide: within ℓ_f / 20.
  scene["bodies"][0]["mesh"] = json::parse(
      R"({ "box": { "min": [-0.5, -0.5, -0.001], "max": [0.5, 0.5, 0.5], "divisions": [2, 2, 2] } })");
  scene["contact"][0]["slave"] = "ball/bottom";
  EXPECT_TRUE(with_code(summary_of(scene), warning::contact_behind_master).empty());
  scene["contact"][0]["master"] = "plate/bottom";  // 0.2 behind: a mistake again
  const auto behind = with_code(summary_of(scene), warning::contact_behind_master);
  ASSERT_EQ(behind.size(), 1u);
  EXPECT_NE(behind[0].message.find("did you mean plate/top?"), std::string::npos) << behind[0].message;
}

TEST(Warnings, SteelWithDensityInGramsPerCubicCentimetreIsAUnitSlip) {
  json scene = seed();
  for (json& body : scene["bodies"]) body["material"].update({{"youngs_modulus", 2e11}, {"density", 7.8}});
  const Summary s = summary_of(scene);
  const auto units = with_code(s, warning::unit_scale);
  ASSERT_EQ(units.size(), 2u);  // one per body
  EXPECT_EQ(units[0].pointer, "/bodies/0/material/density");
  EXPECT_EQ(units[1].pointer, "/bodies/1/material/density");
  EXPECT_NE(units[0].message.find("ρ = 7.8 with E = 2e11: density in g/cm³? In kg/m³ it is 7800"),
            std::string::npos)
      << units[0].message;
  EXPECT_NE(units[0].message.find("√(E/ρ) is 1.6e5"), std::string::npos) << units[0].message;
  // The contact lasts ~2.5e-4 (Hertz), 40 times shorter than the step; the plate's slowest mode 5e-5.
  const auto contact = with_code(s, warning::step_longer_than_contact);
  ASSERT_EQ(contact.size(), 1u);
  EXPECT_EQ(contact[0].pointer, "/time/step");
  EXPECT_NE(contact[0].message.find("less than one step h = 0.01"), std::string::npos) << contact[0].message;
  const auto modes = with_code(s, warning::step_longer_than_modes);
  ASSERT_EQ(modes.size(), 1u);
  EXPECT_NE(modes[0].message.find("spans 200 periods of the slowest mode of plate"), std::string::npos)
      << modes[0].message;
}

// A static step is a load increment (docs/theory.md §5b.6): steel pressed by a punch in 10 load steps of
// 0.1 spans thousands of its periods, which resolves nothing and needs nothing resolved. Only the
// unit check stays (E and ρ in SI here: no warning at all).
TEST(Warnings, StaticLoadStepsGetNoStepWarnings) {
  json scene = json::parse(std::ifstream(examples + "punch.json"));
  for (json& body : scene["bodies"]) body["material"].update({{"youngs_modulus", 2e11}, {"density", 7800}});
  const Summary dynamic_summary = [&] {
    json dynamic = scene;
    dynamic["time"]["scheme"] = "energy_momentum";
    return summary_of(dynamic);
  }();
  ASSERT_EQ(with_code(dynamic_summary, warning::step_longer_than_modes).size(), 1u)
      << "the same scene, dynamic";
  EXPECT_EQ(summary_of(scene).warnings.size(), 0u);
}

TEST(Warnings, AStepFarBelowTheWaveTimeIsReported) {
  json scene = seed();
  scene["time"].update({{"step", 1e-7}, {"end", 1e-3}});  // 10,000 steps, Courant number 1.46e-4
  const auto tiny = with_code(summary_of(scene), warning::step_far_below_waves);
  ASSERT_EQ(tiny.size(), 1u);
  EXPECT_EQ(tiny[0].pointer, "/time/step");
  EXPECT_NE(tiny[0].message.find("is 0.000146 of the time a wave takes"), std::string::npos)
      << tiny[0].message;
}

TEST(Estimates, WaveSpeedsElementSizePeriodAndMassMatchTheFormulas) {
  const Summary s = summary_of(seed());
  ASSERT_EQ(s.estimates.bodies.size(), 2u);
  const BodyScale& plate = s.estimates.bodies[1];
  // E = 1e4, ν = 0.4, ρ = 1: c₀ = 100, c_d = √(1e4·0.6/(1.4·0.2)) (W1).
  EXPECT_NEAR(plate.bar_speed, 100, 1e-9);
  EXPECT_NEAR(plate.dilatational_speed, std::sqrt(1e4 * 0.6 / (1.4 * 0.2)), 1e-9);
  EXPECT_NEAR(plate.smallest_element, 0.1, 1e-12);                          // 0.2 thick in 2 layers
  EXPECT_NEAR(plate.courant, plate.dilatational_speed * 0.01 / 0.1, 1e-9);  // (W2)
  EXPECT_NEAR(plate.lowest_period, 2 * 4 / 100.0, 1e-12);                   // (W3): L = 4
  EXPECT_NEAR(plate.mass, 4 * 4 * 0.2, 1e-12);                              // boxes are exact
}

TEST(Estimates, TheBarsContactLastsTheWaveRoundTrip) {
  const Summary s = summarize(load_file(examples + "colliding_bars.json"));
  ASSERT_EQ(s.estimates.pairs.size(), 1u);
  const PairScale& p = s.estimates.pairs[0];
  const BodyScale& left = s.estimates.bodies[0];
  EXPECT_NEAR(p.approach_speed, 0.2, 1e-12);                                  // ±0.1 along z
  EXPECT_NEAR(p.wave_duration, 2 * left.extent.z() / left.bar_speed, 1e-12);  // (W5)
  EXPECT_EQ(p.duration, std::max(p.wave_duration, p.hertz_duration));         // (W6)
}

TEST(Estimates, TheHertzDurationFollowsTheSphereOnAFlat) {
  const Summary s = summary_of(seed());
  ASSERT_EQ(s.estimates.pairs.size(), 1u);
  const PairScale& p = s.estimates.pairs[0];
  const BodyScale &ball = s.estimates.bodies[0], &plate = s.estimates.bodies[1];
  const double contact_modulus = 1e4 / (2 * (1 - 0.16));
  const double reduced_mass = 1 / (1 / ball.mass + 1 / plate.mass);
  const double radius = ball.extent.minCoeff() / 2;
  const double v = p.approach_speed;
  const double indentation =
      std::pow(15 * reduced_mass * v * v / (16 * contact_modulus * std::sqrt(radius)), 0.4);
  EXPECT_NEAR(p.hertz_duration, 2.94 * indentation / v, 1e-12);  // (W4)
  EXPECT_GT(p.hertz_duration, 0.05);                             // ~10 steps of 0.01: no warning on the seed
  EXPECT_LT(p.hertz_duration, 0.2);
}

TEST(ResolvedChoices, EachPairSaysWhichSurfaceItGotAndWhy) {
  const Summary smooth = summary_of(seed());
  ASSERT_EQ(smooth.choices.size(), 2u);
  EXPECT_EQ(smooth.choices[0].pointer, "/contact/0/master_surface");
  EXPECT_EQ(smooth.choices[0].value, "smooth");
  EXPECT_NE(smooth.choices[0].reason.find("plate/top qualifies"), std::string::npos)
      << smooth.choices[0].reason;
  EXPECT_EQ(smooth.choices[1].pointer, "/contact/0/switch_gap");
  EXPECT_EQ(smooth.choices[1].value, "keep");
  EXPECT_EQ(smooth.choices[1].reason, "the default on a smooth surface");

  json scene = seed();
  scene["contact"][0]["master_surface"] = "faceted";
  const Summary faceted = summary_of(scene);
  EXPECT_EQ(faceted.choices[0].value, "faceted");
  EXPECT_EQ(faceted.choices[0].reason, "the scene asks for it (smooth could be had)");
  EXPECT_EQ(faceted.choices[1].value, "clamp");
  EXPECT_EQ(faceted.choices[1].reason, "the default on a faceted surface");
}

TEST(ResolvedChoices, AMasterThatCannotBeSmoothSaysWhyItIsFaceted) {
  json scene = seed();
  // The whole boundary of a one-element box as master: every corner is extraordinary (valence 3).
  scene["bodies"][1]["mesh"] =
      json::parse(R"({ "box": { "min": [-2, -2, -0.2], "max": [2, 2, 0], "divisions": [1, 1, 1] } })");
  scene["contact"][0]["master"] = "plate/boundary";
  const Summary s = summary_of(scene);
  EXPECT_EQ(s.choices[0].value, "faceted");
  EXPECT_NE(s.choices[0].reason.find("cannot carry a smooth surface"), std::string::npos)
      << s.choices[0].reason;
  EXPECT_NE(s.choices[0].reason.find("faceted is the fallback"), std::string::npos) << s.choices[0].reason;
  EXPECT_EQ(s.choices[1].value, "clamp");
}

TEST(BeforeRunJson, CarriesWarningsAsCodePointerMessage) {
  json scene = seed();
  scene["contact"][0]["master"] = "plate/bottom";
  const json j = before_run_json(summary_of(scene));
  ASSERT_EQ(j["warnings"].size(), 1u);
  EXPECT_EQ(j["warnings"][0], (json{{"code", "contact_behind_master"},
                                    {"pointer", "/contact/0/master"},
                                    {"message",
                                     "every node of ball/outer is behind plate/bottom (its normals point "
                                     "away); did you mean plate/top?"}}));
  EXPECT_EQ(j["choices"][0]["value"], "smooth");
  EXPECT_GT(j["estimates"]["wall_seconds"].get<double>(), 0);
  EXPECT_EQ(j["estimates"]["contact"][0]["pointer"], "/contact/0");
}

TEST(Spelling, AMisspeltFieldSaysWhatWasMeant) {
  json scene = seed();
  scene["bodies"][0]["intial_velocity"] = scene["bodies"][0]["initial_velocity"];
  scene["bodies"][0].erase("initial_velocity");
  scene["time"]["stp"] = 0.01;
  scene["bodies"][1]["colour"] = "red";
  try {
    load(scene);
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    std::map<std::string, std::string> by_pointer;
    for (const Issue& i : e.issues) by_pointer[i.pointer] = i.message;
    EXPECT_EQ(by_pointer["/bodies/0/intial_velocity"], "unknown field; did you mean \"initial_velocity\"?");
    EXPECT_EQ(by_pointer["/time/stp"], "unknown field; did you mean \"step\"?");
    EXPECT_EQ(by_pointer["/bodies/1/colour"], "unknown field");  // nothing close
  }
}

TEST(Spelling, EditDistanceAndClosestName) {
  EXPECT_EQ(detail::edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(detail::edit_distance("", "abc"), 3u);
  EXPECT_EQ(detail::edit_distance("intial_velocity", "initial_velocity"), 1u);
  EXPECT_EQ(detail::closest_name("mu", {"friction", "impact"}), std::nullopt);
  EXPECT_EQ(detail::closest_name("frcition", {"friction", "impact"}), "friction");
}

}  // namespace
}  // namespace stoss::scene
