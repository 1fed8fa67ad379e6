// kill -9 trials (issue 10 item 4): the system shall lose no job and serve no partial result when the process
// computing a run is killed at random moments, and every run resumed from its last checkpoint shall end with
// the result of a run that never crashed, to the Newton tolerance. Two scenes: frictionless Lagrange contact
// (the seed's example shortened) and Coulomb friction with penalty contact (its frictional example
// shortened), a checkpoint every 2 steps, so that the kills land between checkpoints. Killed: `stoss run`
// (then `stoss run --resume DIR`), and a worker of the job service together with its job processes (the
// worker's rescuer and the next worker resume the jobs). Kill moments come from a seeded generator, scaled to
// the wall time of an uncrashed run (so they land mid-run on a quiet machine as on a loaded one); how many
// kills land mid-run is printed (docs/measurements.md, "Hardening numbers").
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <fstream>
#include <random>
#include <thread>

#include "core/output/result_reader.hpp"
#include "core/scene/scene.hpp"
#include "server/jobs/running/inprocess_executor.hpp"
#include "server/jobs/running/process_executor.hpp"
#include "tests/core/short_ball_on_plate.hpp"
#include "tests/server/live_server.hpp"
#include "tests/server/pg_cluster.hpp"

namespace stoss::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

/// The shortened seed's example (tests/core/short_ball_on_plate.hpp), 30 steps with a checkpoint every 2:
/// frictionless Lagrange contact (impact "persist"), or penalty contact with Coulomb friction μ = 0.2.
nlohmann::json short_ball_on_plate(bool friction) {
  return test::short_ball_on_plate(friction ? ShortBallOnPlate{"penalty", "energy_momentum", false, 0.3, 2}
                                            : ShortBallOnPlate{"lagrange", "energy_momentum", true, 0.3, 2});
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// Every series but the wall-time one, and every frame, of two results equal to the Newton tolerance
/// (relative to each series' largest value).
void expect_same_result(const fs::path& reference, const fs::path& result, const std::string& what) {
  SCOPED_TRACE(what);
  const auto a = output::ResultFile::open(reference), b = output::ResultFile::open(result);
  EXPECT_EQ(b.attribute_double("complete"), 1);
  ASSERT_EQ(a.series_names(), b.series_names());
  for (const std::string& name : a.series_names()) {
    if (name == "step_seconds") continue;
    const Eigen::MatrixXd x = a.series(name), y = b.series(name);
    ASSERT_EQ(x.rows(), y.rows()) << name;
    EXPECT_LE((x - y).cwiseAbs().maxCoeff(), 1e-9 * std::max(x.cwiseAbs().maxCoeff(), 1e-300)) << name;
  }
  ASSERT_EQ(a.frame_count(), b.frame_count());
  for (int k = 0; k < a.frame_count(); ++k) {
    EXPECT_EQ(a.frame_times()[k], b.frame_times()[k]);
    EXPECT_LE((a.frame_positions(k) - b.frame_positions(k)).norm(), 1e-9 * a.frame_positions(k).norm()) << k;
    EXPECT_LE((a.frame_velocities(k) - b.frame_velocities(k)).norm(), 1e-9 * a.frame_velocities(k).norm())
        << k;
  }
}

/// Whether `pid` ended by SIGKILL (reaped); false when it exited by itself first (status in `exit_code`).
bool kill9(pid_t pid, int& exit_code) {
  ::kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

/// Steps named by the "resumed from step N" lines of a log, in order.
std::vector<int> resumed_steps(const std::string& log) {
  std::vector<int> steps;
  const std::string key = "resumed from step ";
  for (size_t at = log.find(key); at != std::string::npos; at = log.find(key, at + 1))
    steps.push_back(std::stoi(log.substr(at + key.size())));
  return steps;
}

struct Tally {
  int kills = 0, lost = 0, partial_served = 0, resumed = 0;
};

/// `stoss run SCENE -o DIR` killed after random delays, then `stoss run --resume DIR` (or the first command
/// again when the kill came before it wrote DIR/checkpoint/run.json), killed again, … at most `kills` times,
/// until an attempt ends by itself or the result is there.
/// Kill moments are drawn between 20 % and 80 % of `run_ms`, the wall time of an uncrashed run of the scene,
/// so that the kills land mid-run on a quiet machine as on a loaded one.
void cli_campaign(const fs::path& scene, const fs::path& dir, std::mt19937& rng, int kills, Tally& tally,
                  int run_ms) {
  std::uniform_int_distribution<int> delay_ms(run_ms / 5, run_ms * 4 / 5);
  for (int attempt = 0;; ++attempt) {
    ASSERT_LT(attempt, 60) << "no progress";
    const bool can_resume = fs::exists(dir / output::checkpoint_directory_name / "run.json");
    const std::vector<std::string> args =
        can_resume ? std::vector<std::string>{"run", "--resume", dir.string()}
                   : std::vector<std::string>{"run", scene.string(), "-o", dir.string()};
    const fs::path log = dir.string() + "." + std::to_string(attempt) + ".log";
    const pid_t pid = spawn_stoss(args, log);
    int exit_code = -1;
    bool killed = false;
    if (kills > 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
      killed = kill9(pid, exit_code);
    } else {
      int status = 0;
      waitpid(pid, &status, 0);
      exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
    if (!resumed_steps(read_file(log)).empty()) ++tally.resumed;
    if (fs::exists(dir / output::result_file_name)) {
      // Done, even when the kill came after the result was renamed into place: it is whole.
      if (output::ResultFile::open(dir / output::result_file_name).attribute_double("complete") != 1)
        ++tally.partial_served;
      if (!killed) EXPECT_EQ(exit_code, 0) << read_file(log);
      return;
    }
    if (!killed) {
      ADD_FAILURE() << "exit " << exit_code << " without a result: " << read_file(log);
      ++tally.lost;
      return;
    }
    ++tally.kills;
    --kills;
  }
}

TEST(KillNine, RunsKilledAtRandomStepsResumeFromTheirCheckpointsAndEndAsUncrashedRuns) {
  TempDir tmp;
  std::mt19937 rng(20261129);
  Tally cli, service;
  std::vector<fs::path> scenes, references;
  std::vector<int> run_ms;  // wall time of an uncrashed stoss run of each scene
  for (bool friction : {false, true}) {
    scenes.push_back(tmp.path() / (friction ? "friction.json" : "contact.json"));
    std::ofstream(scenes.back()) << short_ball_on_plate(friction).dump();
    const fs::path reference = tmp.path() / (friction ? "friction_reference" : "contact_reference");
    const auto t0 = std::chrono::steady_clock::now();
    const CommandResult uncrashed =
        run_stoss({"run", scenes.back().string(), "-o", reference.string()}, 120s);
    run_ms.push_back(static_cast<int>(
        std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - t0)
            .count()));
    ASSERT_EQ(uncrashed.exit_code, 0) << uncrashed.out << uncrashed.err;
    EXPECT_FALSE(
        fs::exists(reference / output::checkpoint_directory_name));  // removed once the result is there
    references.push_back(reference / output::result_file_name);
  }

  // The command line: stoss run, then stoss run --resume DIR; the two scenes in turn.
  for (int campaign = 0; cli.kills < 10; ++campaign) {
    ASSERT_LT(campaign, 20) << "the kills land after the runs ended";
    const size_t k = campaign % 2;
    const fs::path dir = tmp.path() / ("cli" + std::to_string(campaign));
    cli_campaign(scenes[k], dir, rng, 4, cli, run_ms[k]);
    expect_same_result(references[k], dir / output::result_file_name, "stoss run --resume " + dir.string());
  }

  // The job service: an API server that only queues and serves, and a worker killed with its job processes;
  // a new pair of jobs whenever the last pair finished, until 10 kills landed mid-run.
  const fs::path data = tmp.path() / "data";
  const std::vector<std::string> fast_rescue = {"--lease-seconds", "1", "--renew-seconds", "0.2",
                                                "--max-attempts",  "60"};
  std::vector<std::string> api_args = {"--workers", "0"};
  api_args.insert(api_args.end(), fast_rescue.begin(), fast_rescue.end());
  LiveServer api(data, api_args);
  auto c = api.client();
  std::vector<std::pair<std::string, size_t>> jobs;  // id, scene
  const auto submit_pair = [&] {
    for (size_t k : {0, 1}) jobs.emplace_back(body_json(submit(c, short_ball_on_plate(k == 1)))["id"], k);
  };
  submit_pair();
  std::vector<std::string> worker_args = {"--workers", "2"};
  worker_args.insert(worker_args.end(), fast_rescue.begin(), fast_rescue.end());
  const std::string store = "sqlite:" + (data / "jobs.db").string();
  std::uniform_int_distribution<int> delay_ms(0, std::min(run_ms[0], run_ms[1]) / 2);
  const auto unfinished = [&] {
    std::vector<std::string> ids;
    for (const auto& [id, k] : jobs)
      if (job(c, id)["status"] != "succeeded") ids.push_back(id);
    return ids;
  };
  for (int round = 0; service.kills < 10; ++round) {
    ASSERT_LT(round, 60) << "the jobs stopped making progress";
    LiveWorker worker(store, data, worker_args);
    // Wait until a job computes (a step after its start or resume), then a random moment more.
    const bool computing = eventually(
        [&] {
          const auto ids = unfinished();
          if (ids.empty()) return true;
          for (const auto& id : ids) {
            const auto j = job(c, id);
            if (j["status"] == "running" && j["progress"]["step"].get<int>() >= 1) return true;
          }
          return false;
        },
        60s);
    ASSERT_TRUE(computing);
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
    std::vector<pid_t> job_processes;
    for (const auto& id : unfinished()) {
      const int attempt = job(c, id)["attempt"];
      std::ifstream in(data / "jobs" / id / ("attempt-" + std::to_string(attempt)) /
                       server::jobs::job_pid_file);
      pid_t pid = -1;
      if (in >> pid && pid > 0 && ::kill(pid, 0) == 0) job_processes.push_back(pid);
    }
    if (job_processes.empty()) {
      submit_pair();
      continue;
    }
    worker.kill9();
    for (pid_t pid : job_processes)
      ::kill(pid, SIGKILL);  // they die with the worker anyway (PR_SET_PDEATHSIG)
    service.kills += static_cast<int>(job_processes.size());
    for (const auto& [id, k] : jobs) {
      const auto result = c.Get("/v1/jobs/" + id + "/result");
      if (result->status != 409 && job(c, id)["status"] != "succeeded") ++service.partial_served;
    }
  }
  {
    LiveWorker worker(store, data, worker_args);  // the last worker runs the jobs to their end
    for (const auto& [id, k] : jobs) {
      const auto done = wait_for_status(c, id, {"succeeded", "failed", "canceled"}, 120s);
      EXPECT_EQ(done["status"], "succeeded") << done.dump();
      if (done["status"] != "succeeded") ++service.lost;
      if (!resumed_steps(c.Get("/v1/jobs/" + id + "/log")->body).empty()) ++service.resumed;
      const auto result = c.Get("/v1/jobs/" + id + "/result");
      ASSERT_EQ(result->status, 200);
      const fs::path file = tmp.path() / (id + ".h5");
      std::ofstream(file, std::ios::binary) << result->body;
      expect_same_result(references[k], file, "job " + id + ", attempt " + done["attempt"].dump());
      for (const auto& attempt : fs::directory_iterator(data / "jobs" / id))  // every attempt's is pruned
        EXPECT_FALSE(fs::exists(attempt.path() / output::checkpoint_directory_name)) << attempt.path();
    }
  }

  std::printf(
      "kill -9 trials: %d mid-run kills (stoss run %d, job service %d), jobs lost %d, partial results served "
      "%d, attempts that resumed from a checkpoint %d\n",
      cli.kills + service.kills, cli.kills, service.kills, cli.lost + service.lost,
      cli.partial_served + service.partial_served, cli.resumed + service.resumed);
  EXPECT_GE(cli.kills + service.kills, 20);
  EXPECT_EQ(cli.lost + service.lost, 0);
  EXPECT_EQ(cli.partial_served + service.partial_served, 0);
  EXPECT_GE(cli.resumed + service.resumed, 5);
}

TEST(KillNine, AJobGivenBackAtAGracefulShutdownGoesOnFromItsCheckpoint) {
  TempDir tmp;
  const fs::path data = tmp.path() / "data";
  LiveServer api(data, {"--workers", "0"});
  auto c = api.client();
  nlohmann::json scene = short_ball_on_plate(false);
  scene["time"]["end"] = 0.6;  // 60 steps: still running when the worker stops
  const std::string id = body_json(submit(c, scene))["id"];
  const std::string store = "sqlite:" + (data / "jobs.db").string();
  {
    LiveWorker worker(store, data, {"--workers", "1"});
    ASSERT_TRUE(eventually([&] { return job(c, id)["progress"]["step"].get<int>() >= 8; }, 60s));
  }  // SIGTERM: the job stops within a step and goes back to the queue
  EXPECT_EQ(job(c, id)["status"], "queued");
  LiveWorker worker(store, data, {"--workers", "1"});
  const auto done = wait_for_status(c, id, {"succeeded", "failed", "canceled"}, 120s);
  EXPECT_EQ(done["status"], "succeeded") << done.dump();
  const std::vector<int> resumed = resumed_steps(c.Get("/v1/jobs/" + id + "/log")->body);
  ASSERT_EQ(resumed.size(), 1u);
  EXPECT_GE(resumed[0], 8);
  EXPECT_EQ(done["summary"]["resumed_from_step"], resumed[0]);
}

TEST(KillNine, AJobWhoseCheckpointCannotBeReadStartsOverAndSucceeds) {
  TempDir tmp;
  const server::jobs::JobFiles files(tmp.path());
  server::jobs::Job job;
  job.id = server::jobs::JobId::random();
  job.kind = server::jobs::Kind::simulation;
  job.attempt = 2;
  nlohmann::json scene = short_ball_on_plate(false);
  scene["time"]["end"] = 0.05;
  job.scene = scene::load(scene).scene;  // as POST stores it: validated, defaults filled in
  // Attempt 1 left a torn checkpoint; attempt 2 starts from a copy of it, in its own folder.
  const fs::path torn = files.attempt(job.id, 1).checkpoint() / "state.h5";
  fs::create_directories(torn.parent_path());
  std::ofstream(torn) << "a torn file, not HDF5";
  server::jobs::SystemClock clock;
  server::jobs::InProcessExecutor executor(files, clock);
  const std::atomic<bool> cancel{false};
  const server::jobs::Outcome outcome = executor.run(job, cancel, {});
  EXPECT_EQ(outcome.status, server::jobs::Status::succeeded) << outcome.error.value_or("");
  const server::jobs::AttemptFiles second = files.attempt(job.id, 2);
  const std::string log = read_file(second.log());
  EXPECT_NE(log.find("cannot resume from " + (second.checkpoint() / "state.h5").string()), std::string::npos)
      << log;
  EXPECT_NE(log.find("; starting from step 0"), std::string::npos) << log;
  EXPECT_TRUE(fs::exists(second.result()));
  EXPECT_FALSE(fs::exists(second.checkpoint()));
  EXPECT_FALSE(fs::exists(torn)) << "a succeeded attempt prunes the checkpoints of the attempts before it";
  EXPECT_EQ(server::jobs::outcome_from_json(nlohmann::json::parse(read_file(second.outcome_file()))).status,
            server::jobs::Status::succeeded);
}

}  // namespace
}  // namespace stoss::test
