// Jobs on several MPI ranks through the service (issue 27 §5, docs/many_machines.md "Jobs on several
// ranks"): a scene's solver.ranks runs under the launcher on a worker that may run it, with the answers of
// one rank and the memory of every rank; cancel, the wall-time limit and kill -9 of the server leave no rank
// running; a launch that cannot start fails the job with the launcher's message.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include "tests/server/live_server.hpp"
#include "tests/server/rank_answers.hpp"

namespace stoss::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

TEST(JobRanks, ATwoRankJobGivesTheAnswersOfOneRankAndCountsTheMemoryOfBoth) {
  if (one_core()) GTEST_SKIP() << "one core: mpiexec has one slot";
  TempDir dir;
  const PrivateTemp temp(dir);
  const fs::path data = dir.path() / "data";
  LiveServer server(data, two_rank_service());
  auto c = server.client();
  const auto [one, two, a, b] = seed_jobs_on_one_and_two_ranks(c);
  ASSERT_FALSE(HasFailure());
  EXPECT_EQ(b["ranks"], 2);
  EXPECT_EQ(b["progress"]["step"], 20) << "rank 0's progress reached the server through the launcher";
  EXPECT_NE(c.Get("/v1/jobs/" + two + "/log")->body.find("on 2 MPI ranks"), std::string::npos);
  const fs::path one_result = last_attempt(data, a), two_result = last_attempt(data, b);
  ASSERT_FALSE(HasFailure());
  expect_the_same_answers(one_result, two_result);
  // Each rank holds the whole model: the two together use well over what one does.
  EXPECT_GT(b["summary"]["peak_memory_mb"].get<double>(), 1.5 * a["summary"]["peak_memory_mb"].get<double>());
  EXPECT_EQ(temp.rank_directories_left(), std::vector<std::string>{}) << "rank 1's private folder is removed";
}

TEST(JobRanks, ACanceledTwoRankJobStopsEveryRankAtOneStepEvenWhileItStarts) {
  if (one_core()) GTEST_SKIP() << "one core: mpiexec has one slot";
  TempDir dir;
  const PrivateTemp temp(dir);
  LiveServer server(dir.path() / "data", two_rank_service());
  auto c = server.client();
  const std::string id = id_of(submit(c, long_two_rank_scene()));
  ASSERT_TRUE(eventually([&] { return job(c, id)["progress"]["step"].get<int>() >= 2; }, 120s));
  EXPECT_EQ(processes_of(id), 3) << "the launcher and two ranks";
  const auto folders = temp.rank_directories_left();
  ASSERT_EQ(folders.size(), 1u) << "rank 1's private folder while it runs";
  for (const char* name : {"result.h5.partial", "result.h5"})
    EXPECT_FALSE(fs::exists(fs::path(folders[0]) / name)) << "rank 0 alone writes the result: " << name;
  ASSERT_EQ(c.Post("/v1/jobs/" + id + "/cancel")->status, 202);
  const auto canceled = wait_for_status(c, id, {"canceled", "failed", "succeeded"}, 60s);
  EXPECT_EQ(canceled["status"], "canceled") << canceled.dump();
  EXPECT_GE(canceled["summary"]["steps"].get<int>(), 2) << canceled.dump();
  EXPECT_NE(c.Get("/v1/jobs/" + id + "/log")->body.find("canceled at step"), std::string::npos);
  EXPECT_TRUE(eventually([&] { return processes_of(id) == 0; }, 10s)) << "no rank is left running";
  EXPECT_EQ(temp.rank_directories_left(), std::vector<std::string>{});

  // A cancel while the launcher or the ranks start is a cancel too.
  const std::string early = id_of(submit(c, long_two_rank_scene()));
  ASSERT_TRUE(eventually([&] { return job(c, early)["status"] == "running"; }, 60s));
  ASSERT_EQ(c.Post("/v1/jobs/" + early + "/cancel")->status, 202);
  EXPECT_EQ(wait_for_status(c, early, {"canceled", "failed", "succeeded"}, 20s)["status"], "canceled");
  EXPECT_TRUE(eventually([&] { return processes_of(early) == 0; }, 10s)) << "no rank is left running";
}

TEST(JobRanks, TheWallTimeLimitLeavesNoRankRunning) {
  if (one_core()) GTEST_SKIP() << "one core: mpiexec has one slot";
  TempDir dir;
  LiveServer server(dir.path() / "data", two_rank_service({"--job-timeout", "4"}));
  auto c = server.client();
  const std::string timed = id_of(submit(c, long_two_rank_scene()));
  const auto failed = wait_for_status(c, timed, {"canceled", "failed", "succeeded"}, 60s);
  EXPECT_EQ(failed["error"], "exceeded wall-time limit 4 s") << failed.dump();
  EXPECT_TRUE(eventually([&] { return processes_of(timed) == 0; }, 10s)) << "no rank is left running";
}

TEST(JobRanks, KillNineOfTheServerLeavesNoRankRunningAndTheJobResumesOnTwoRanks) {
  if (one_core()) GTEST_SKIP() << "one core: mpiexec has one slot";
  TempDir dir;
  const PrivateTemp temp(dir);
  const fs::path data = dir.path() / "data";
  const auto flags = two_rank_service({"--lease-seconds", "1", "--renew-seconds", "0.2"});
  nlohmann::json scene = box_scene(6, 300, {1, 0, 0}, 2.0);
  scene["solver"]["ranks"] = 2;
  scene["output"]["checkpoint_every"] = 10;
  std::string id;
  {
    LiveServer server(data, flags);
    auto c = server.client();
    id = id_of(submit(c, scene));
    ASSERT_TRUE(eventually([&] { return job(c, id)["progress"]["step"].get<int>() >= 25; }, 60s));
    ASSERT_EQ(processes_of(id), 3);
    server.kill9();
    EXPECT_TRUE(eventually([&] { return processes_of(id) == 0; }, 10s))
        << "the launcher dies with the server, the ranks with the launcher";
  }
  LiveServer again(data, flags);
  auto c = again.client();
  const auto done = wait_for_status(c, id, {"succeeded", "failed", "canceled"}, 120s);
  ASSERT_EQ(done["status"], "succeeded") << done.dump();
  EXPECT_EQ(done["attempt"], 2);
  const std::string log = c.Get("/v1/jobs/" + id + "/log")->body;
  EXPECT_NE(log.find("resumed from step"), std::string::npos) << log;
  EXPECT_NE(log.find("on 2 MPI ranks"), std::string::npos) << log;
  EXPECT_LT(done["summary"]["energy_drift"].get<double>(), 1e-9) << "resumed, the energy still holds";
  EXPECT_EQ(temp.rank_directories_left(), std::vector<std::string>{});
}

TEST(JobRanks, ALaunchThatCannotStartFailsTheJobWithTheLaunchersMessage) {
  TempDir dir;
  LiveServer server(dir.path() / "data",
                    two_rank_service({"--launcher", "mpiexec -n {ranks} --no-such-option …"}));
  auto c = server.client();
  nlohmann::json scene = box_scene(2, 10);
  scene["solver"]["ranks"] = 2;
  const std::string id = id_of(submit(c, scene));
  const auto failed = wait_for_status(c, id, {"canceled", "failed", "succeeded"}, 60s);
  EXPECT_EQ(failed["status"], "failed");
  EXPECT_EQ(failed["error"].get<std::string>().rfind("the launcher exited with status 1: ", 0), 0)
      << failed.dump();
  EXPECT_NE(failed["error"].get<std::string>().find("unknown option \"--no-such-option\""), std::string::npos)
      << failed.dump();
  EXPECT_EQ(processes_of(id), 0);
}

TEST(JobRanks, ALauncherThatStartsAnotherCountOfRanksFailsTheJobNamingBoth) {
  TempDir dir;
  const std::string one_rank = std::string("mpiexec -n 1") + (geteuid() == 0 ? " --allow-run-as-root" : "");
  LiveServer server(dir.path() / "data", two_rank_service({"--launcher", one_rank}));
  auto c = server.client();
  nlohmann::json scene = box_scene(2, 10);
  scene["solver"]["ranks"] = 2;
  const std::string id = id_of(submit(c, scene));
  const auto failed = wait_for_status(c, id, {"canceled", "failed", "succeeded"}, 60s);
  EXPECT_EQ(failed["error"],
            "the launcher started 1 ranks, the job asks for 2 (solver.ranks): see --launcher's {ranks}")
      << failed.dump();
  EXPECT_TRUE(eventually([&] { return processes_of(id) == 0; }, 10s));
}

}  // namespace
}  // namespace stoss::test
