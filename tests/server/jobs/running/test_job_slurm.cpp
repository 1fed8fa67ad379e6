// Runs on several ranks placed by Slurm (issue 27 §5, docs/many_machines.md "Jobs on several ranks"), on a
// Slurm cluster of this machine that the test starts (tests/server/slurm_cluster.hpp): `srun` runs `stoss
// run` on 2 ranks with the answers of one, and the service's `--launcher "srun --mpi=pmix -n {ranks} …"`
// runs a two-rank job with them too; a cancel and the wall-time limit leave no rank running.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "tests/server/live_server.hpp"
#include "tests/server/rank_answers.hpp"
#include "tests/server/slurm_cluster.hpp"

namespace stoss::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const std::string srun_launcher = "srun --mpi=pmix -n {ranks} --kill-on-bad-exit=1";

TEST(SlurmRanks, SrunRunsStossRunOnTwoRanksWithTheAnswersOfOne) {
  if (const std::string why = SlurmCluster::unavailable(); !why.empty()) GTEST_SKIP() << why;
  if (one_core()) GTEST_SKIP() << "one core";
  TempDir dir;
  const PrivateTemp temp(dir);
  const SlurmCluster cluster;
  const std::string scene = seed_in_contact(dir, "petsc_gamg");
  const fs::path one = dir.path() / "one", two = dir.path() / "two", log = dir.path() / "srun.log";
  ASSERT_EQ(run_stoss({"run", scene, "-o", one.string()}, 120s).exit_code, 0);
  const std::string srun = "srun --mpi=pmix -n 2 " + std::string(STOSS_BINARY) + " run " + scene + " -o " +
                           two.string() + " > " + log.string() + " 2>&1";
  ASSERT_EQ(std::system(srun.c_str()), 0) << read_text(log) << cluster.logs();
  EXPECT_NE(read_text(log).find("the sum over 2 MPI ranks"), std::string::npos)
      << "each srun task found its place (SLURM_PROCID of SLURM_STEP_NUM_TASKS): " << read_text(log);
  expect_the_same_answers(one, two);
  EXPECT_EQ(temp.rank_directories_left(), std::vector<std::string>{});
}

TEST(SlurmRanks, TheServiceRunsATwoRankJobUnderSrunAndACancelLeavesNoRank) {
  if (const std::string why = SlurmCluster::unavailable(); !why.empty()) GTEST_SKIP() << why;
  if (one_core()) GTEST_SKIP() << "one core";
  TempDir dir;
  const PrivateTemp temp(dir);
  const SlurmCluster cluster;  // SLURM_CONF reaches the server's launcher through its environment
  const fs::path data = dir.path() / "data";
  LiveServer server(data, two_rank_service({"--launcher", srun_launcher}));
  auto c = server.client();
  const auto [one, two, a, b] = seed_jobs_on_one_and_two_ranks(c);
  ASSERT_FALSE(HasFailure());
  EXPECT_NE(c.Get("/v1/jobs/" + two + "/log")->body.find("on 2 MPI ranks"), std::string::npos);
  const fs::path one_result = last_attempt(data, a), two_result = last_attempt(data, b);
  ASSERT_FALSE(HasFailure());
  expect_the_same_answers(one_result, two_result);

  const std::string id = id_of(submit(c, long_two_rank_scene()));
  ASSERT_TRUE(eventually([&] { return job(c, id)["progress"]["step"].get<int>() >= 2; }, 120s));
  EXPECT_GE(processes_of(id), 3) << "srun (with its helper) and the two ranks Slurm started";
  ASSERT_EQ(c.Post("/v1/jobs/" + id + "/cancel")->status, 202);
  const auto canceled = wait_for_status(c, id, {"canceled", "failed", "succeeded"}, 60s);
  EXPECT_EQ(canceled["status"], "canceled") << canceled.dump();
  EXPECT_TRUE(eventually([&] { return processes_of(id) == 0; }, 20s)) << "no rank is left running";
  EXPECT_EQ(temp.rank_directories_left(), std::vector<std::string>{});
}

TEST(SlurmRanks, TheWallTimeLimitEndsTheSrunStepAndLeavesNoRank) {
  if (const std::string why = SlurmCluster::unavailable(); !why.empty()) GTEST_SKIP() << why;
  if (one_core()) GTEST_SKIP() << "one core";
  TempDir dir;
  const SlurmCluster cluster;
  LiveServer server(dir.path() / "data",
                    two_rank_service({"--launcher", srun_launcher, "--job-timeout", "6"}));
  auto c = server.client();
  const std::string timed = id_of(submit(c, long_two_rank_scene()));
  const auto failed = wait_for_status(c, timed, {"canceled", "failed", "succeeded"}, 90s);
  EXPECT_EQ(failed["error"], "exceeded wall-time limit 6 s") << failed.dump();
  EXPECT_TRUE(eventually([&] { return processes_of(timed) == 0; }, 30s))
      << "Slurm ends the step of a killed srun: no rank is left running";
}

}  // namespace
}  // namespace stoss::test
