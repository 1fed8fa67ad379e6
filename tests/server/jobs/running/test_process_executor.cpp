// A crashing job fails alone (issue 10): every job runs in a process of its own, supervised by the
// server. A job process killed by a signal or past a limit fails that job with the reason named; the
// server, and the job running beside it, go on without losing an attempt.
#include <gtest/gtest.h>
#include <signal.h>

#include <fstream>
#include <regex>

#include "server/jobs/running/process_executor.hpp"
#include "tests/server/live_server.hpp"

namespace stoss::test {
namespace {

using namespace std::chrono_literals;

std::string id_of(const httplib::Result& r) {
  return body_json(r)["id"].get<std::string>();
}

/// The pid of job `id`'s first attempt's process while it runs (DATA/jobs/<id>/attempt-1/process.pid), or -1.
pid_t job_pid(const std::filesystem::path& data, const std::string& id) {
  std::ifstream in(data / "jobs" / id / "attempt-1" / server::jobs::job_pid_file);
  pid_t pid = -1;
  in >> pid;
  return in ? pid : -1;
}

/// A job that runs for minutes unless stopped.
nlohmann::json long_scene() {
  return box_scene(4, 100'000, {1, 0, 0}, 2.0);
}

bool running_with_progress(httplib::Client& c, const std::string& id) {
  const auto j = job(c, id);
  return j["status"] == "running" && j["progress"]["step"].get<int>() >= 1;
}

TEST(JobProcess, ASignalFailsThatJobAloneWithTheSignalNamed) {
  TempDir dir;
  const auto data = dir.path() / "data";
  LiveServer server(data, {"--workers", "2"});
  auto c = server.client();
  const std::string victim = id_of(submit(c, long_scene())), bystander = id_of(submit(c, long_scene()));
  ASSERT_TRUE(eventually(
      [&] { return running_with_progress(c, victim) && running_with_progress(c, bystander); }, 120s));
  const pid_t victim_pid = job_pid(data, victim), bystander_pid = job_pid(data, bystander);
  ASSERT_GT(victim_pid, 0);
  ASSERT_GT(bystander_pid, 0);
  EXPECT_NE(victim_pid, server.pid());
  EXPECT_NE(victim_pid, bystander_pid);

  ASSERT_EQ(::kill(victim_pid, SIGSEGV), 0);
  auto failed = wait_for_status(c, victim, {"failed", "succeeded", "canceled"}, 60s);
  EXPECT_EQ(failed["status"], "failed");
  EXPECT_EQ(failed["error"], "killed by signal SIGSEGV");
  EXPECT_EQ(failed["attempt"], 1);  // a crash of the job is the job's failure: no retry
  EXPECT_NE(c.Get("/v1/jobs/" + victim + "/log")->body.find("failed: killed by signal SIGSEGV"),
            std::string::npos);
  EXPECT_EQ(c.Get("/v1/jobs/" + victim + "/result")->status, 409);

  // The server and the other job go on, the other job in its first attempt.
  ASSERT_TRUE(server.alive()) << server.output();
  EXPECT_EQ(c.Get("/healthz")->status, 200);
  const auto still = job(c, bystander);
  EXPECT_EQ(still["status"], "running");
  EXPECT_EQ(still["attempt"], 1);
  const int step_before = still["progress"]["step"];
  EXPECT_TRUE(
      eventually([&] { return job(c, bystander)["progress"]["step"].get<int>() > step_before; }, 30s));

  ASSERT_EQ(::kill(bystander_pid, SIGKILL), 0);
  failed = wait_for_status(c, bystander, {"failed", "succeeded", "canceled"}, 60s);
  EXPECT_EQ(failed["status"], "failed");
  EXPECT_EQ(failed["error"], "killed by signal SIGKILL");
  EXPECT_EQ(failed["attempt"], 1);

  // A new job runs as usual.
  const std::string after = id_of(submit(c, box_scene(2, 10)));
  const auto done = wait_for_status(c, after, {"succeeded", "failed"}, 60s);
  EXPECT_EQ(done["status"], "succeeded") << done.dump();
  EXPECT_EQ(done["attempt"], 1);
  EXPECT_TRUE(server.alive()) << server.output();
}

TEST(JobProcess, AJobOverItsWallTimeLimitFailsWithTheLimitNamed) {
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "2", "--job-timeout", "2"});
  auto c = server.client();
  nlohmann::json limited = long_scene();
  limited["solver"] = {{"max_wall_seconds", 1}};  // lower than the server's: it wins
  const std::string by_scene = id_of(submit(c, limited)), by_server = id_of(submit(c, long_scene()));
  const auto a = wait_for_status(c, by_scene, {"failed", "succeeded", "canceled"}, 60s);
  const auto b = wait_for_status(c, by_server, {"failed", "succeeded", "canceled"}, 60s);
  EXPECT_EQ(a["status"], "failed");
  EXPECT_EQ(a["error"], "exceeded wall-time limit 1 s");
  EXPECT_EQ(b["status"], "failed");
  EXPECT_EQ(b["error"], "exceeded wall-time limit 2 s");
  EXPECT_EQ(c.Get("/v1/jobs/" + by_scene + "/result")->status, 409);
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "data/jobs" / by_scene / "attempt-1/log.txt"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "data/jobs" / by_scene / "attempt-1/result.h5.partial"));
  // A short job under the same limits succeeds.
  const std::string quick = id_of(submit(c, box_scene(2, 10)));
  EXPECT_EQ(wait_for_status(c, quick, {"succeeded", "failed"}, 60s)["status"], "succeeded");
}

TEST(JobProcess, AJobOverItsMemoryLimitFailsWithTheLimitNamed) {
  TempDir dir;
  LiveServer server(dir.path() / "data",
                    {"--workers", "1", "--job-memory", "300000000", "--max-nodes", "1000000"});
  auto c = server.client();
  const std::string big = id_of(submit(c, box_scene(40, 10)));  // 68921 nodes: far more than 300 MB
  const auto failed = wait_for_status(c, big, {"failed", "succeeded", "canceled"}, 120s);
  EXPECT_EQ(failed["status"], "failed");
  EXPECT_EQ(failed["error"], "exceeded memory limit 300000000 bytes (--job-memory)") << failed.dump();
  const std::string small = id_of(submit(c, box_scene(2, 10)));
  EXPECT_EQ(wait_for_status(c, small, {"succeeded", "failed"}, 60s)["status"], "succeeded");
}

TEST(JobProcess, AScenesWallTimeLimitIsValidated) {
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "0"});
  auto c = server.client();
  nlohmann::json scene = box_scene(2, 10);
  scene["solver"] = {{"max_wall_seconds", -1}};
  auto r = c.Post("/v1/validate", scene.dump(), "application/json");
  EXPECT_EQ(r->status, 422);
  EXPECT_NE(r->body.find("/solver/max_wall_seconds"), std::string::npos) << r->body;
  scene = box_scene(2, 10);
  scene["output"]["every"] = 4294967296.0;
  r = c.Post("/v1/validate", scene.dump(), "application/json");
  EXPECT_EQ(r->status, 422);
  EXPECT_NE(r->body.find("/output/every"), std::string::npos) << r->body;
}

TEST(JobProcess, WallLimitIsTheLowerOfServerAndScene) {
  server::jobs::Job job;
  job.scene = box_scene(2, 10);
  EXPECT_EQ(server::jobs::ProcessExecutor::wall_limit(job, 0), 0);
  EXPECT_EQ(server::jobs::ProcessExecutor::wall_limit(job, 5000), 5000);
  job.scene["solver"] = {{"max_wall_seconds", 2.5}};
  EXPECT_EQ(server::jobs::ProcessExecutor::wall_limit(job, 0), 2500);
  EXPECT_EQ(server::jobs::ProcessExecutor::wall_limit(job, 5000), 2500);
  EXPECT_EQ(server::jobs::ProcessExecutor::wall_limit(job, 1000), 1000);
  EXPECT_EQ(server::jobs::signal_reason(SIGSEGV), "killed by signal SIGSEGV");
}

}  // namespace
}  // namespace stoss::test

namespace stoss::test {
namespace {

TEST(PartialResults, SeriesAndSummaryOfRunningFailedAndCanceledJobsAreReadableAndMarkedIncomplete) {
  TempDir dir;
  const auto data = dir.path() / "data";
  LiveServer server(data, {"--workers", "2"});
  auto c = server.client();
  const std::string running = id_of(submit(c, long_scene())), doomed = id_of(submit(c, long_scene()));
  ASSERT_TRUE(eventually(
      [&] { return running_with_progress(c, running) && running_with_progress(c, doomed); }, 120s));
  // Running: the series so far (flushed a few times a second), completed: false; no result.
  nlohmann::json series;
  ASSERT_TRUE(eventually(
      [&] {
        auto r = c.Get("/v1/jobs/" + running + "/series");
        if (!r || r->status != 200) return false;
        series = nlohmann::json::parse(r->body);
        return series["time"].size() >= 2;
      },
      30s));
  EXPECT_EQ(series["completed"], false);
  EXPECT_EQ(series["summary"]["completed"], false);
  EXPECT_GE(series["summary"]["steps"].get<int>(), 1);
  EXPECT_EQ(series["time"].size(), series["kinetic_energy"].size());
  EXPECT_EQ(series["linear_momentum"][0].size(), 3u);
  auto csv = c.Get("/v1/jobs/" + running + "/series?format=csv");
  EXPECT_EQ(csv->status, 200);
  EXPECT_EQ(csv->get_header_value("Stoss-Completed"), "false");
  EXPECT_EQ(csv->body.rfind("time,kinetic_energy,", 0), 0u) << csv->body.substr(0, 200);
  EXPECT_EQ(c.Get("/v1/jobs/" + running + "/result")->status, 409);

  // Failed (its process killed): the summary up to the last recorded step, and the series.
  ASSERT_EQ(::kill(job_pid(data, doomed), SIGKILL), 0);
  const auto failed = wait_for_status(c, doomed, {"failed", "succeeded", "canceled"}, 60s);
  ASSERT_EQ(failed["status"], "failed");
  EXPECT_EQ(failed["summary"]["completed"], false) << failed.dump();
  EXPECT_GE(failed["summary"]["steps"].get<int>(), 1) << failed.dump();
  auto failed_series = c.Get("/v1/jobs/" + doomed + "/series");
  EXPECT_EQ(failed_series->status, 200);
  EXPECT_EQ(body_json(failed_series)["completed"], false);
  EXPECT_EQ(c.Get("/v1/jobs/" + doomed + "/result")->status, 409);

  // Canceled: the same.
  EXPECT_EQ(c.Post("/v1/jobs/" + running + "/cancel")->status, 202);
  const auto canceled = wait_for_status(c, running, {"canceled", "failed", "succeeded"}, 60s);
  ASSERT_EQ(canceled["status"], "canceled");
  EXPECT_EQ(canceled["summary"]["completed"], false);
  const auto canceled_series = body_json(c.Get("/v1/jobs/" + running + "/series"));
  EXPECT_EQ(canceled_series["completed"], false);
  EXPECT_GE(canceled_series["time"].size(), series["time"].size());
  EXPECT_EQ(c.Get("/v1/jobs/" + running + "/result")->status, 409);

  // A queued job has no series yet.
  LiveServer idle(dir.path() / "idle", {"--workers", "0"});
  auto ic = idle.client();
  const std::string queued = id_of(submit(ic, box_scene(2, 10)));
  EXPECT_EQ(ic.Get("/v1/jobs/" + queued + "/series")->status, 409);
}

TEST(PartialResults, AFrictionalJobsSummaryCarriesTheDissipatedEnergy) {
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "1"});
  auto c = server.client();
  nlohmann::json scene = nlohmann::json::parse(
      std::ifstream(std::string(STOSS_SOURCE_DIR) + "/api/examples/hollow_ball_plate_friction.json"));
  scene["time"]["end"] = 0.4;  // 40 steps: the ball lands and slides on the plate
  const std::string id = id_of(submit(c, scene));
  const auto done = wait_for_status(c, id, {"succeeded", "failed"}, 300s);
  ASSERT_EQ(done["status"], "succeeded") << done.dump();
  const auto& summary = done["summary"];
  ASSERT_TRUE(summary.contains("dissipated_energy")) << summary.dump();
  ASSERT_TRUE(summary.contains("energy_plus_dissipated_drift")) << summary.dump();
  EXPECT_GT(summary["dissipated_energy"].get<double>(), 0.0);
  // Energy lost to friction is accounted for: the balance drifts far less than the energy alone.
  EXPECT_LT(summary["energy_plus_dissipated_drift"].get<double>(), summary["energy_drift"].get<double>());
  // The series' last dissipated_energy is the summary's.
  const auto series = body_json(c.Get("/v1/jobs/" + id + "/series"));
  EXPECT_DOUBLE_EQ(series["dissipated_energy"].back().get<double>(),
                   summary["dissipated_energy"].get<double>());
  // Solver lines in the log name their step and the time it starts from (the format is checked in
  // tests/server/jobs/reporting/test_job_observer.cpp; with today's Newton this run may need no line search
  // at all).
  const std::string log = c.Get("/v1/jobs/" + id + "/log")->body;
  EXPECT_FALSE(std::regex_search(log, std::regex(R"((^|\n)newton:)"))) << "a solver line without its step:\n"
                                                                       << log;
}

}  // namespace
}  // namespace stoss::test
