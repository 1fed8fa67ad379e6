// A study's tolerances (issue 22 §2): POST /v1/studies takes `tolerances` beside `steps`; each must be a
// finite number > 0, else a 422 naming /tolerances/i and the rule; the runs count them; the finest run a
// tolerance allows (end/min_step) is held to max_steps as a scene with time.tolerance is.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace stoss::server::http
