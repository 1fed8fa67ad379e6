// What POST /v1/jobs and POST /v1/validate check of a scene before anything is queued (issue 27 §5): a scene
// may ask for at most --max-ranks-per-job MPI ranks (solver.ranks); more is a 422 naming /solver/ranks and
// the service's limit, since no worker of the service would ever claim the job.
#include <gtest/gtest.h>

#include "server/http/scene_check.hpp"
#include "tests/server/live_server.hpp"

namespace stoss::server::http {
namespace {

/// A small valid box scene asking for `ranks` MPI ranks.
nlohmann::json scene_on_ranks(int ranks) {
  nlohmann::json scene = test::box_scene(1, 10);
  scene["solver"]["ranks"] = ranks;
  return scene;
}

/// The problem check_scene throws for `scene` (fails the test when it accepts it).
Problem problem_of(const nlohmann::json& scene, const Limits& limits) {
  try {
    check_scene(scene, limits);
  } catch (const ProblemError& e) {
    return e.problem();
  }
  ADD_FAILURE() << "check_scene accepted " << scene.dump();
  return {};
}

TEST(SceneCheck, MoreRanksThanMaxRanksPerJobIs422AtSolverRanksNamingTheLimit) {
  const Problem p = problem_of(scene_on_ranks(2), Limits{});
  EXPECT_EQ(p.status, 422);
  EXPECT_EQ(p.type, "urn:stoss:problem:invalid-scene");
  const nlohmann::json& errors = p.extra.at("errors");
  ASSERT_EQ(errors.size(), 1u) << errors.dump();
  EXPECT_EQ(errors[0]["pointer"], "/solver/ranks");
  EXPECT_EQ(errors[0]["message"],
            "must be at most 1 on this service (stoss serve --max-ranks-per-job 1), got 2");
  EXPECT_EQ(p.detail,
            "the scene has 1 error, the first: /solver/ranks: must be at most 1 on this service (stoss serve "
            "--max-ranks-per-job 1), got 2");
  Limits four;
  four.max_ranks_per_job = 4;
  EXPECT_EQ(problem_of(scene_on_ranks(5), four).extra.at("errors")[0]["message"],
            "must be at most 4 on this service (stoss serve --max-ranks-per-job 4), got 5");
}

TEST(SceneCheck, RanksWithinMaxRanksPerJobAreAcceptedAndKeptInTheResolvedScene) {
  Limits two;
  two.max_ranks_per_job = 2;
  nlohmann::json resolved;
  EXPECT_EQ(check_scene(scene_on_ranks(2), two, {}, &resolved).ranks, 2);
  EXPECT_EQ(resolved["solver"]["ranks"], 2);
  EXPECT_EQ(check_scene(scene_on_ranks(1), Limits{}).ranks, 1);
  EXPECT_EQ(check_scene(test::box_scene(1, 10), Limits{}, {}, &resolved).ranks, 1) << "absent: one rank";
  EXPECT_FALSE(resolved["solver"].contains("ranks")) << "and not filled in";
}

TEST(SceneCheck, AnInvalidRanksIsTheValidatorsErrorNotTheServiceLimit) {
  const Problem p = problem_of(scene_on_ranks(0), Limits{});
  ASSERT_EQ(p.extra.at("errors").size(), 1u) << p.extra.dump();
  EXPECT_EQ(p.extra["errors"][0]["pointer"], "/solver/ranks");
  EXPECT_EQ(p.extra["errors"][0]["message"], "must be in [1, 4096], got 0");
}

}  // namespace
}  // namespace stoss::server::http
