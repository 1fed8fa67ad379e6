// The command line: the system shall validate scenes (effects and counts, or every error by JSON
// pointer; exit 2), run them into DIR/result.h5 + result.xdmf with a summary (exit 0), and on a solver
// failure name the step and time, exit 1 and leave only result.incomplete.h5 (issue: foundation, CLI).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/output/result_reader.hpp"
#include "server/cli/progress.hpp"
#include "tests/server/live_server.hpp"

namespace stoss {
namespace {

namespace fs = std::filesystem;

struct Command {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr
};

Command stoss(const std::string& args) {
  const std::string line = std::string(STOSS_BINARY) + " " + args + " 2>&1";
  FILE* pipe = popen(line.c_str(), "r");
  Command c;
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof buffer, pipe)) c.output.append(buffer, n);
  const int status = pclose(pipe);
  c.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
  return c;
}

nlohmann::json bar_scene() {
  std::ifstream in(std::string(STOSS_SOURCE_DIR) + "/api/examples/tumbling_bar.json");
  nlohmann::json scene = nlohmann::json::parse(in);
  scene["time"]["end"] = 0.2;  // 4 steps
  return scene;
}

std::string write(const test::TempDir& dir, const nlohmann::json& scene) {
  const fs::path path = dir.path() / "scene.json";
  std::ofstream(path) << scene.dump(2);
  return path.string();
}

TEST(Cli, ValidatePrintsEffectsCountsAndSteps) {
  const Command c =
      stoss("validate " + std::string(STOSS_SOURCE_DIR) + "/api/examples/hollow_ball_plate.json");
  EXPECT_EQ(c.exit_code, 0) << c.output;
  EXPECT_NE(c.output.find("effects: inertia elasticity contact_frictionless"), std::string::npos) << c.output;
  EXPECT_NE(c.output.find("nodes 1521, elements 944, dofs 4563"), std::string::npos) << c.output;
  EXPECT_NE(c.output.find("steps 100"), std::string::npos) << c.output;
}

TEST(Cli, ValidateNamesEveryErrorByPointerAndExits2) {
  test::TempDir dir;
  nlohmann::json scene = bar_scene();
  scene["bodies"][0]["material"]["poisson_ratio"] = 0.5;
  scene["time"]["step"] = -1;
  const Command c = stoss("validate " + write(dir, scene));
  EXPECT_EQ(c.exit_code, 2);
  EXPECT_NE(c.output.find("/bodies/0/material/poisson_ratio"), std::string::npos) << c.output;
  EXPECT_NE(c.output.find("/time/step"), std::string::npos) << c.output;
}

TEST(Cli, RunWritesACompleteResultAndPrintsTheSummary) {
  test::TempDir dir;
  const Command c = stoss("run " + write(dir, bar_scene()) + " -o " + (dir.path() / "out").string());
  ASSERT_EQ(c.exit_code, 0) << c.output;
  EXPECT_NE(c.output.find("steps 4, t = 0.2"), std::string::npos) << c.output;
  EXPECT_NE(c.output.find("energy drift"), std::string::npos) << c.output;
  EXPECT_EQ(c.output.find("max penetration"), std::string::npos) << "no contact, no penetration line";
  EXPECT_TRUE(fs::exists(dir.path() / "out/result.xdmf"));
  const output::ResultFile result = output::ResultFile::open(dir.path() / "out/result.h5");
  EXPECT_EQ(result.attribute_double("complete"), 1);
  EXPECT_EQ(result.series("time").rows(), 5) << "t0 and every step";
}

// issue 23 §4: a run with loads names its external work and measures the drift of H − W_ext.
TEST(Cli, RunWithALoadPrintsTheExternalWorkAndTheDriftOfHMinusW) {
  test::TempDir dir;
  nlohmann::json scene = bar_scene();
  const std::string body = scene["bodies"][0]["name"];
  scene["loads"] = {{{"surface", body + "/top"}, {"traction", {0, 0, 1}}}};
  const Command c = stoss("run " + write(dir, scene) + " -o " + (dir.path() / "out").string());
  ASSERT_EQ(c.exit_code, 0) << c.output;
  EXPECT_NE(c.output.find("external work "), std::string::npos) << c.output;
  EXPECT_NE(c.output.find("(H − W_ext, relative, max over steps)"), std::string::npos) << c.output;
  const Command free = stoss("run " + write(dir, bar_scene()) + " -o " + (dir.path() / "free").string());
  EXPECT_EQ(free.output.find("external work"), std::string::npos) << "no loads: no external work line";
}

// Static load steps are equilibria at each load level: no energy is kept between them, so no drift is
// printed.
TEST(Cli, StaticRunSaysItsEnergyDriftIsNotReported) {
  test::TempDir dir;
  nlohmann::json scene = bar_scene();
  const std::string body = scene["bodies"][0]["name"];
  scene["time"] = {{"scheme", "static"}, {"step", 0.5}, {"end", 1}};
  scene["bodies"][0].erase("initial_velocity");
  scene["bodies"][0].erase("initial_angular_velocity");
  scene["boundary"] = {{{"surface", body + "/bottom"}, {"fix", "xyz"}}};
  scene["loads"] = {{{"surface", body + "/top"}, {"traction", {0, 0, 1}}, {"amplitude", {{0, 0}, {1, 1}}}}};
  const Command c = stoss("run " + write(dir, scene) + " -o " + (dir.path() / "out").string());
  ASSERT_EQ(c.exit_code, 0) << c.output;
  EXPECT_NE(c.output.find("external work "), std::string::npos) << c.output;
  EXPECT_NE(c.output.find("energy drift: not reported (static load steps)"), std::string::npos) << c.output;
  EXPECT_EQ(c.output.find("max over steps)"), std::string::npos) << c.output;
}

// A suspect run (docs/results.md "Verdict"): an iteration cap of 10 puts the Newton bound at
// 0.6 · 10 = 6 iterations per step, and the tumbling bar takes 7. The result is kept either way; the
// warning block names the failed check, result.h5 carries verdict and checks, and --strict exits 3.
TEST(Cli, SuspectRunWarnsKeepsItsResultAndExits3WithStrict) {
  test::TempDir dir;
  nlohmann::json scene = bar_scene();
  scene["solver"]["max_iterations"] = 10;
  const std::string path = write(dir, scene), out = (dir.path() / "out").string();
  const Command plain = stoss("run " + path + " -o " + out);
  EXPECT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_NE(plain.output.find("verdict: suspect"), std::string::npos) << plain.output;
  EXPECT_NE(plain.output.find("  newton_iterations_per_step = "), std::string::npos) << plain.output;
  EXPECT_NE(plain.output.find("momentum drift: linear"), std::string::npos) << "the bar is free";
  const output::ResultFile result = output::ResultFile::open(dir.path() / "out/result.h5");
  EXPECT_EQ(result.attribute_string("verdict"), "suspect");
  const nlohmann::json checks = nlohmann::json::parse(result.attribute_string("checks"));
  ASSERT_TRUE(checks.is_array());
  bool newton_failed = false;
  for (const auto& c : checks)
    if (c.at("name") == "newton_iterations_per_step") newton_failed = !c.at("passed").get<bool>();
  EXPECT_TRUE(newton_failed) << checks.dump();
  const Command strict = stoss("run " + path + " -o " + out + " --strict");
  EXPECT_EQ(strict.exit_code, 3) << strict.output;
  scene["solver"].erase("max_iterations");
  const Command ok = stoss("run " + write(dir, scene) + " -o " + out + " --strict");
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(ok.output.find("verdict: ok"), std::string::npos) << ok.output;
}

TEST(Cli, ContactRunsReportPenetration) {
  test::TempDir dir;
  const Command c = stoss("run " + std::string(STOSS_SOURCE_DIR) + "/api/examples/colliding_bars.json -o " +
                          (dir.path() / "out").string());
  ASSERT_EQ(c.exit_code, 0) << c.output;
  const size_t at = c.output.find("max penetration ");
  ASSERT_NE(at, std::string::npos) << c.output;
  EXPECT_LT(std::stod(c.output.substr(at + 16)), 1e-3 * 0.1) << "below 0.1 % of the 0.1 face size";
}

TEST(Cli, SolverFailureNamesTheStepExits1AndLeavesOnlyAnIncompleteResult) {
  test::TempDir dir;
  nlohmann::json scene = bar_scene();
  scene["solver"] = {{"tolerance", 1e-14}, {"max_iterations", 1}};  // one iteration cannot reach 1e-14
  const Command c = stoss("run " + write(dir, scene) + " -o " + (dir.path() / "out").string());
  EXPECT_EQ(c.exit_code, 1) << c.output;
  EXPECT_NE(c.output.find("step 1"), std::string::npos) << c.output;
  EXPECT_NE(c.output.find("t = "), std::string::npos) << c.output;
  EXPECT_FALSE(fs::exists(dir.path() / "out/result.h5"));
  const output::ResultFile partial = output::ResultFile::open(dir.path() / "out/result.incomplete.h5");
  EXPECT_EQ(partial.attribute_double("complete"), 0);
}

// `stoss study --tolerances` (issue 22 §2): a row per scheme and tolerance, steps chosen by time.tolerance
// from the scene's first step; it carries its tolerance and beats the coarse fixed step it sits beside.
TEST(Cli, StudyTakesTolerancesBesideSteps) {
  test::TempDir dir;
  nlohmann::json scene = bar_scene();
  scene["time"]["end"] = 0.4;
  const Command c = stoss("study " + write(dir, scene) +
                          " --steps 0.1 --tolerances 1e-3 --schemes energy_momentum --repeat 1 --json");
  ASSERT_EQ(c.exit_code, 0) << c.output;
  const nlohmann::json table = nlohmann::json::parse(c.output);
  ASSERT_EQ(table["rows"].size(), 2u) << c.output;
  const nlohmann::json &fixed = table["rows"][0], &adaptive = table["rows"][1];
  EXPECT_FALSE(fixed.contains("tolerance"));
  EXPECT_EQ(adaptive["tolerance"], 1e-3);
  EXPECT_EQ(adaptive["step"], 0.05) << "the first step is the scene's time.step";
  ASSERT_TRUE(adaptive["completed"].get<bool>()) << c.output;
  const double error = adaptive["displacement_error"].get<double>();
  EXPECT_TRUE(std::isfinite(error));
  EXPECT_LT(error, fixed["displacement_error"].get<double>()) << c.output;
  EXPECT_LE(error, 10 * 1e-3) << "within 10 × its tolerance";
  EXPECT_GT(adaptive["steps"].get<int>(), 4);
  EXPECT_EQ(stoss("study " + write(dir, scene) + " --steps 0.1 --tolerances 1e-3,0").exit_code, 2);
  const Command infinite = stoss("study " + write(dir, scene) + " --steps 0.1 --tolerances inf");
  EXPECT_EQ(infinite.exit_code, 2);
  EXPECT_NE(infinite.output.find("--tolerances: every tolerance must be a finite number > 0"),
            std::string::npos)
      << infinite.output;
}

// The progress line of `stoss run` (server/cli/progress.hpp): steps of N with fixed steps; with a tolerance
// the share of simulated time done and an ETA from the time rate.
TEST(Cli, ProgressLineGoesBySimulatedTimeWithATolerance) {
  model::Model m;
  m.time.step = 0.01;
  m.time.end = 1.0;
  cli::ProgressObserver fixed(nullptr);
  fixed.begin(m, {});
  EXPECT_EQ(fixed.line({25, 0.25, {}}, 2.0), "step 25/100  t = 0.25/1  elapsed 2.0 s  ETA 6.0 s");
  m.time.tolerance = 1e-3;
  cli::ProgressObserver adaptive(nullptr);
  adaptive.begin(m, {});
  EXPECT_EQ(adaptive.line({250, 0.4, {}}, 2.0), "step 250  t = 0.4/1 (40 %)  elapsed 2.0 s  ETA 3.0 s")
      << "0.4 of simulated time in 2 s: 0.6 to go in 3 s, whatever the steps";
  adaptive.step({0, 0, {}});
  adaptive.step({10, 0.8, {}});
  adaptive.resumed(10);
  EXPECT_EQ(adaptive.line({12, 0.9, {}}, 1.0), "step 12  t = 0.9/1 (90 %)  elapsed 1.0 s  ETA 1.0 s")
      << "a resumed run's rate counts from the checkpoint's time";
}

TEST(Cli, UnknownCommandAndMissingSceneAreUsageErrors) {
  EXPECT_EQ(stoss("frobnicate").exit_code, 2);
  const Command c = stoss("run /nonexistent/scene.json");
  EXPECT_EQ(c.exit_code, 2);
  EXPECT_NE(c.output.find("/nonexistent/scene.json"), std::string::npos) << c.output;
}

}  // namespace
}  // namespace stoss
