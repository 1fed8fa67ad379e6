// The system shall give every run a verdict (issue 25 §1, docs/results.md "Verdict"): every shipped
// example (api/examples/*.json, run to its end) ends "ok" with each check passed, and two newcomer
// mistakes end "suspect" naming the check that caught them:
// - the seed's example with "master": "plate/bottom" (the plate's normals point away from the ball):
//   contact pumps energy into the run as reported jumps; shortened to t = 0.45, where the ball is in
//   the plate and Σ contact_energy_jump already exceeds 5 % of H_0 (the full run's H reaches ~640 H_0);
// - steel with its density in g/cm³ (E = 2e11, ρ = 7.8) on the seed's example: a wave speed of 1.6e5 makes
//   every step stiff beyond what Newton can follow, and the first step alone takes ~230 iterations;
// - the frictional example with a normal_stiffness of 10 instead of the default 10 E ℓ (a stiffness
//   typed in other units): the ball sinks into the plate deeper than half an element.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/scene/scene.hpp"
#include "core/simulate.hpp"

namespace stoss {
namespace {

namespace fs = std::filesystem;

std::string failed_checks(const model::Summary& s) {
  std::string out;
  for (const model::Check& c : s.checks)
    if (!c.passed) out += c.name + " = " + std::to_string(c.value) + " > " + std::to_string(c.bound) + "; ";
  return out;
}

bool failed(const model::Summary& s, const std::string& name) {
  return std::any_of(s.checks.begin(), s.checks.end(),
                     [&](const model::Check& c) { return c.name == name && !c.passed; });
}

nlohmann::json example(const std::string& name) {
  return nlohmann::json::parse(std::ifstream(std::string(STOSS_SOURCE_DIR) + "/api/examples/" + name));
}

model::Summary run(const nlohmann::json& scene) {
  model::Observer quiet;
  return simulate(scene::load(scene, fs::path(STOSS_SOURCE_DIR) / "api/examples"), quiet);
}

class ShippedExample : public testing::TestWithParam<std::string> {};

TEST_P(ShippedExample, EndsOk) {
  const model::Summary s = run(example(GetParam()));
  ASSERT_TRUE(s.completed);
  EXPECT_GE(s.checks.size(), 3u) << "energy, Newton iterations and step reductions are always checked";
  EXPECT_EQ(s.verdict, "ok") << failed_checks(s);
}

std::vector<std::string> shipped_examples() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(fs::path(STOSS_SOURCE_DIR) / "api/examples"))
    if (entry.path().extension() == ".json") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

INSTANTIATE_TEST_SUITE_P(Verdict, ShippedExample, testing::ValuesIn(shipped_examples()),
                         [](const testing::TestParamInfo<std::string>& info) {
                           return fs::path(info.param).stem().string();
                         });

TEST(Verdict, WrongMasterSurfaceIsSuspectForItsEnergy) {
  nlohmann::json scene = example("hollow_ball_plate.json");
  scene["contact"][0]["master"] = "plate/bottom";
  scene["time"]["end"] = 0.45;
  const model::Summary s = run(scene);
  ASSERT_TRUE(s.completed) << "a suspect run still completes";
  EXPECT_EQ(s.verdict, "suspect");
  EXPECT_TRUE(failed(s, "contact_energy_jumps")) << failed_checks(s);
}

TEST(Verdict, DensityInGramsPerCubicCentimetreIsSuspectForItsNewtonIterations) {
  nlohmann::json scene = example("hollow_ball_plate.json");
  for (auto& body : scene["bodies"]) body["material"].update({{"youngs_modulus", 2e11}, {"density", 7.8}});
  scene["time"]["end"] = scene["time"]["step"];  // one step shows it (measured: 3 steps, 233 its/step)
  const model::Summary s = run(scene);
  ASSERT_TRUE(s.completed);
  EXPECT_EQ(s.verdict, "suspect");
  EXPECT_TRUE(failed(s, "newton_iterations_per_step")) << failed_checks(s);
  EXPECT_FALSE(failed(s, "energy_balance")) << "energy–momentum still keeps its energy";
}

TEST(Verdict, NormalStiffnessInOtherUnitsIsSuspectForItsPenetration) {
  nlohmann::json scene = example("hollow_ball_plate_friction.json");
  scene["contact"][0]["normal_stiffness"] = 10.0;  // the default 10 E ℓ is ~2.5e4
  const model::Summary s = run(scene);
  ASSERT_TRUE(s.completed);
  EXPECT_EQ(s.verdict, "suspect");
  EXPECT_TRUE(failed(s, "penetration")) << failed_checks(s);
  EXPECT_FALSE(failed(s, "energy_plus_dissipated_rise")) << "the soft penalty keeps its energy promise";
}

}  // namespace
}  // namespace stoss
