// A study's tolerances (issue 22 §2): POST /v1/studies takes `tolerances` beside `steps`; each must be a
// finite number > 0, else a 422 naming /tolerances/i and the rule; the runs count them; the finest run a
// tolerance allows (end/min_step) is held to max_steps as a scene with time.tolerance is.
#include <gtest/gtest.h>

#include <algorithm>

#include "server/http/study_check.hpp"
#include "tests/server/live_server.hpp"

namespace stoss::server::http {
namespace {

/// A 20-step box swept at h = 0.02 and with one tolerance, energy_momentum only.
nlohmann::json tolerance_study() {
  nlohmann::json body = test::study_body(test::box_scene(1, 20), {0.02}, {"energy_momentum"});
  body["tolerances"] = {1e-3};
  return body;
}

/// The problem check_study throws for `body` (fails the test when it accepts it).
Problem problem_of(const nlohmann::json& body, const Limits& limits = {}) {
  try {
    check_study(body, limits);
  } catch (const ProblemError& e) {
    return e.problem();
  }
  ADD_FAILURE() << "check_study accepted " << body.dump();
  return {};
}

TEST(StudyCheck, TolerancesAreSweptBesideStepsAndCountedAsRuns) {
  nlohmann::json body = tolerance_study();
  body["tolerances"] = {1e-3, 1e-4};
  body["repeat"] = 2;
  const StudyRequest request = check_study(body, Limits{});
  EXPECT_EQ(request.options.tolerances, (std::vector<double>{1e-3, 1e-4}));
  EXPECT_EQ(request.runs, 1 + 1 * (1 + 2) * 2) << "the reference, then 2 runs of each step and tolerance";
  body.erase("tolerances");
  EXPECT_TRUE(check_study(body, Limits{}).options.tolerances.empty());
  EXPECT_EQ(check_study(body, Limits{}).runs, 1 + 2);
}

TEST(StudyCheck, ATolerancesThatIsNotFiniteAndPositiveIs422WithItsPointer) {
  nlohmann::json body = tolerance_study();
  body["tolerances"] = {1e-3, 0, -1e-4, "1e-3", nullptr};
  const Problem p = problem_of(body);
  EXPECT_EQ(p.status, 422);
  EXPECT_EQ(p.type, "urn:stoss:problem:invalid-study");
  const nlohmann::json& errors = p.extra.at("errors");
  ASSERT_EQ(errors.size(), 4u) << errors.dump();
  EXPECT_EQ(errors[0]["pointer"], "/tolerances/1");
  EXPECT_EQ(errors[0]["message"], "must be a finite number > 0, got 0");
  EXPECT_EQ(errors[1]["pointer"], "/tolerances/2");
  EXPECT_EQ(errors[1]["message"], "must be a finite number > 0, got -0.0001");
  EXPECT_EQ(errors[2]["message"], "must be a finite number > 0, got \"1e-3\"");
  EXPECT_EQ(errors[3]["pointer"], "/tolerances/4");
  EXPECT_EQ(p.detail, "the study has 4 errors, the first: /tolerances/1: must be a finite number > 0, got 0");
}

TEST(StudyCheck, TolerancesMustBeANonEmptyArray) {
  for (const nlohmann::json& bad : {nlohmann::json(1e-3), nlohmann::json::array(), nlohmann::json("1e-3")}) {
    nlohmann::json body = tolerance_study();
    body["tolerances"] = bad;
    const nlohmann::json errors = problem_of(body).extra.at("errors");
    ASSERT_EQ(errors.size(), 1u) << errors.dump();
    EXPECT_EQ(errors[0]["pointer"], "/tolerances");
    EXPECT_EQ(
        errors[0]["message"].get<std::string>().rfind("must be an array of 1 to 100 tolerances, got ", 0), 0u)
        << errors[0]["message"];
  }
}

// The box's first step 0.01 gives min_step = 0.01/1024: 0.2 / min_step = 20,480 steps at most, the
// reference at h = 0.02/32 only 320.
TEST(StudyCheck, ATolerancesFinestRunIsEndOverMinStepAgainstMaxSteps) {
  Limits limits;
  limits.max_steps = 10'000;
  nlohmann::json body = tolerance_study();
  const Problem p = problem_of(body, limits);
  EXPECT_EQ(p.status, 413);
  EXPECT_EQ(p.extra.at("limits")[0]["value"], 20'480);
  EXPECT_EQ(
      p.detail,
      "the study's finest run (a tolerance run at its min_step, h = 9.76563e-06) has 20480 time steps, more "
      "than the server limit max_steps = 10000");
  body["scene"]["time"]["tolerance"] = 1e-3;  // the scene's own min_step then bounds the tolerance runs
  body["scene"]["time"]["min_step"] = 1e-4;
  EXPECT_EQ(check_study(body, limits).options.tolerances.size(), 1u);
  body.erase("tolerances");  // without tolerances the scene's min_step is not counted
  body["scene"]["time"]["min_step"] = 1e-6;
  EXPECT_EQ(check_study(body, limits).runs, 4);
}

TEST(StudyCheck, AnUnknownMemberNamesTolerancesAmongTheMembers) {
  nlohmann::json body = tolerance_study();
  body["tolerance"] = 1e-3;
  const nlohmann::json errors = problem_of(body).extra.at("errors");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0]["pointer"], "/tolerance");
  EXPECT_EQ(errors[0]["message"],
            "is not a member of a study (scene, steps, tolerances, schemes, reference_step, repeat)");
}

// `repeat` (issue 25 §5): runs of each point whose median wall time the row shows, an integer in [1, 9],
// 3 when absent; anything else is a 422 at /repeat that says the rule and the value.
TEST(StudyCheck, RepeatIsAnIntegerFrom1To9And3ByDefault) {
  nlohmann::json body = test::study_body(test::box_scene(1, 20), {0.02}, {"energy_momentum"});
  EXPECT_EQ(check_study(body, Limits{}).options.repeat, 3);
  EXPECT_EQ(check_study(body, Limits{}).runs, 1 + 3);
  for (int n : {1, 9}) {
    body["repeat"] = n;
    EXPECT_EQ(check_study(body, Limits{}).options.repeat, n);
    EXPECT_EQ(check_study(body, Limits{}).runs, 1 + n);
  }
  const std::pair<nlohmann::json, std::string> bad[] = {{0, "0"},
                                                        {-1, "-1"},
                                                        {10, "10"},
                                                        {1.5, "1.5"},
                                                        {"3", "\"3\""},
                                                        {nullptr, "null"},
                                                        {nlohmann::json::array({3}), "an array"}};
  for (const auto& [value, shown] : bad) {
    body["repeat"] = value;
    const Problem p = problem_of(body);
    EXPECT_EQ(p.status, 422) << value.dump();
    EXPECT_EQ(p.type, "urn:stoss:problem:invalid-study");
    const nlohmann::json& errors = p.extra.at("errors");
    ASSERT_EQ(errors.size(), 1u) << errors.dump();
    EXPECT_EQ(errors[0]["pointer"], "/repeat");
    EXPECT_EQ(errors[0]["message"], "must be an integer in [1, 9], got " + shown);
  }
}

// Through the live service: a study with repeat = 3 runs each point three times, its table keeps the three
// timings and shows their median; repeat = 0 is refused at its pointer.
TEST(StudyCheck, ALiveStudyWithRepeat3KeepsThreeTimingsAndTheirMedian) {
  test::TempDir dir;
  test::LiveServer server(dir.path() / "data");
  auto c = server.client();
  nlohmann::json body = test::study_body(test::box_scene(1, 20, {0, 0, 0}, 2.0), {0.04}, {"midpoint"});
  body["repeat"] = 0;
  auto refused = test::submit_study(c, body);
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 422) << refused->body;
  EXPECT_EQ(test::body_json(refused)["errors"][0]["pointer"], "/repeat") << refused->body;

  body["repeat"] = 3;
  auto created = test::submit_study(c, body);
  ASSERT_TRUE(created);
  ASSERT_EQ(created->status, 201) << created->body;
  const std::string id = test::body_json(created)["id"];
  EXPECT_EQ(test::body_json(created)["study"]["repeat"], 3);
  ASSERT_EQ(test::wait_for_status(c, id, {"succeeded", "failed", "canceled"})["status"], "succeeded");
  const nlohmann::json table = test::body_json(c.Get("/v1/jobs/" + id + "/study"));
  EXPECT_EQ(table["repeat"], 3);
  EXPECT_EQ(table["timing"], "wall seconds: the median of 3 runs");
  ASSERT_EQ(table["rows"].size(), 1u) << table.dump();
  std::vector<double> runs = table["rows"][0]["wall_seconds_runs"].get<std::vector<double>>();
  ASSERT_EQ(runs.size(), 3u) << table.dump();
  std::sort(runs.begin(), runs.end());
  EXPECT_GT(runs[0], 0);
  EXPECT_EQ(table["rows"][0]["wall_seconds"].get<double>(), runs[1]) << table.dump();
  EXPECT_EQ(test::job(c, id)["summary"]["runs_done"], 4) << "the reference and the point 3 times";
}

// Issue 27 §5: a study runs all its runs in one process, on one rank, whatever --max-ranks-per-job allows.
TEST(StudyCheck, AStudyWhoseSceneAsksForMoreThanOneRankIs422AtItsSolverRanks) {
  nlohmann::json body = tolerance_study();
  body["scene"]["solver"]["ranks"] = 2;
  Limits generous;
  generous.max_ranks_per_job = 8;
  const Problem p = problem_of(body, generous);
  EXPECT_EQ(p.status, 422);
  EXPECT_EQ(p.type, "urn:stoss:problem:invalid-study");
  const nlohmann::json& errors = p.extra.at("errors");
  ASSERT_EQ(errors.size(), 1u) << errors.dump();
  EXPECT_EQ(errors[0]["pointer"], "/scene/solver/ranks");
  EXPECT_EQ(errors[0]["message"], "must be 1: a study runs its runs on one rank, got 2");
  ASSERT_EQ(problem_of(body, Limits{}).extra.at("errors").size(), 1u) << "one error, not the service's too";
  body["scene"]["solver"]["ranks"] = 1;
  EXPECT_EQ(check_study(body, Limits{}).summary.ranks, 1);
}

}  // namespace
}  // namespace stoss::server::http
