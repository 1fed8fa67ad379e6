// Many processes, one PostgreSQL store (issue 15): API processes (`stoss serve --workers 0`) and worker
// processes (`stoss worker`) share a database on a throwaway cluster and one data directory. The system
// shall run every accepted job exactly once when nothing fails, rerun a killed worker's job elsewhere,
// answer 503 with Retry-After while the database is away and recover by itself, and carry a cancel to a
// job running in another process.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <mutex>
#include <regex>
#include <set>
#include <thread>

#include "server/jobs/store/pg.hpp"
#include "tests/server/live_server.hpp"
#include "tests/server/pg_cluster.hpp"

namespace stoss::test {
namespace {

namespace pg = server::jobs::pg;

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// A database of its own in a cluster of its own (the restart test stops the cluster).
struct Database {
  PgCluster cluster;
  std::string name = cluster.create_database();
  std::string url = cluster.url(name);

  std::int64_t count(const std::string& where) {
    return pg::Connection(url).exec("SELECT count(*) FROM stoss_jobs WHERE " + where).int64(0, 0);
  }
  /// The worker holding job `id` ("" when none).
  std::string worker(const std::string& id) {
    auto r = pg::Connection(url).exec("SELECT coalesce(worker, '') FROM stoss_jobs WHERE id = $1", {id});
    return r.rows() ? r.text(0, 0) : "";
  }
};

std::string post_job(httplib::Client& c, const nlohmann::json& scene, int* status = nullptr,
                     bool* retry_after = nullptr) {
  auto r = c.Post("/v1/jobs", scene.dump(), "application/json");
  if (status) *status = r ? r->status : 0;
  if (retry_after) *retry_after = r && r->has_header("Retry-After");
  if (!r || r->status != 201) return "";
  return nlohmann::json::parse(r->body)["id"];
}

nlohmann::json get_job(httplib::Client& c, const std::string& id) {
  auto r = c.Get("/v1/jobs/" + id);
  return r && r->status == 200 ? nlohmann::json::parse(r->body) : nlohmann::json();
}

/// The pid in a worker name "host:pid:suffix/index".
pid_t worker_pid(const std::string& worker) {
  std::smatch m;
  std::regex_search(worker, m, std::regex(R"(^[^:]+:(\d+):)"));
  return m.empty() ? -1 : std::stoi(m[1]);
}

TEST(PgManyProcesses, ThreeHundredJobsThroughTwoApisAndThreeWorkersEachSucceedExactlyOnce) {
  Database db;
  TempDir data;
  LiveServer api_a(data.path(), {"--store", db.url, "--workers", "0"});
  LiveServer api_b(data.path(), {"--store", db.url, "--workers", "0"});
  std::vector<std::unique_ptr<LiveWorker>> workers;
  for (int i = 0; i < 3; ++i)
    workers.push_back(
        std::make_unique<LiveWorker>(db.url, data.path(), std::vector<std::string>{"--workers", "2"}));

  constexpr int jobs = 300;
  std::mutex mutex;
  std::vector<std::string> ids;
  std::vector<std::thread> submitters;
  for (LiveServer* api : {&api_a, &api_b})
    submitters.emplace_back([&, api] {
      auto c = api->client();
      for (int i = 0; i < jobs / 2; ++i) {
        const std::string id = post_job(c, box_scene(1, 1));
        std::lock_guard lock(mutex);
        ids.push_back(id);
      }
    });
  for (auto& t : submitters) t.join();
  ASSERT_EQ(ids.size(), static_cast<std::size_t>(jobs));
  EXPECT_EQ(std::count(ids.begin(), ids.end(), ""), 0) << "every submission is accepted (201)";

  ASSERT_TRUE(eventually([&] { return db.count("status = 'succeeded'") == jobs; }, std::chrono::seconds(120)))
      << db.count("status = 'succeeded'") << " of " << jobs << " succeeded";
  EXPECT_EQ(db.count("attempt <> 1"), 0) << "no job was claimed twice";
  std::set<pid_t> ran_in;
  auto c = api_b.client();
  for (const std::string& id : ids) {
    const std::string log = read_text(data.path() / "jobs" / id / "attempt-1/log.txt");
    // One attempt line and one result per job: nothing ran (or wrote its result) twice.
    const auto lines_starting = [&](const std::string& prefix) {
      int n = 0;
      for (std::size_t at = 0; at < log.size(); at = log.find('\n', at) + 1) {
        if (log.compare(at, prefix.size(), prefix) == 0) ++n;
        if (log.find('\n', at) == std::string::npos) break;
      }
      return n;
    };
    EXPECT_EQ(lines_starting("attempt "), 1) << log;
    EXPECT_EQ(lines_starting("run "), 1) << log;
    ASSERT_EQ(log.rfind("attempt 1 started ", 0), 0u) << log;
    EXPECT_NE(log.find("run completed: 1 steps"), std::string::npos) << log;
    EXPECT_TRUE(std::filesystem::exists(data.path() / "jobs" / id / "attempt-1/result.h5"));
    const std::string worker = log.substr(log.find(" by ") + 4, log.find('\n') - log.find(" by ") - 4);
    ran_in.insert(worker_pid(worker));
  }
  for (auto& w : workers) EXPECT_EQ(ran_in.count(w->pid()), 1u) << "worker " << w->pid() << " ran jobs";
  EXPECT_EQ(ran_in.size(), 3u) << "only worker processes run jobs (the APIs have --workers 0)";
}

TEST(PgManyProcesses, AKilledWorkersJobRerunsInAnotherAndACancelReachesAnotherProcess) {
  Database db;
  TempDir data;
  LiveServer api_a(data.path(), {"--store", db.url, "--workers", "0"});
  LiveServer api_b(data.path(), {"--store", db.url, "--workers", "0"});
  const std::vector<std::string> lease = {"--workers", "1", "--lease-seconds", "2", "--renew-seconds", "0.5"};
  auto first = std::make_unique<LiveWorker>(db.url, data.path(), lease);
  auto second = std::make_unique<LiveWorker>(db.url, data.path(), lease);
  auto a = api_a.client();
  auto b = api_b.client();

  // kill -9 of the worker running a job: after its lease expires, the other worker runs it to success.
  const std::string doomed = post_job(a, box_scene(3, 2500, {1, 0.5, 0}, 2));  // about 2 s of steps
  ASSERT_FALSE(doomed.empty());
  // Mid-job: the job process has started its attempt (its first log line) and not finished.
  nlohmann::json job;
  ASSERT_TRUE(eventually(
      [&] {
        job = get_job(b, doomed);
        return job.value("status", "") == "running" &&
               read_text(data.path() / "jobs" / doomed / "attempt-1/log.txt").find("attempt 1 started") !=
                   std::string::npos;
      },
      std::chrono::seconds(30)))
      << job.dump();
  const pid_t victim = worker_pid(db.worker(doomed));
  LiveWorker& killed = victim == first->pid() ? *first : *second;
  LiveWorker& survivor = victim == first->pid() ? *second : *first;
  ASSERT_EQ(killed.pid(), victim) << job.dump();
  killed.kill9();
  ASSERT_TRUE(eventually([&] { return get_job(b, doomed).value("status", "") == "succeeded"; },
                         std::chrono::seconds(60)))
      << get_job(b, doomed).dump();
  job = get_job(a, doomed);
  EXPECT_EQ(job["attempt"], 2);
  const std::string log = b.Get("/v1/jobs/" + doomed + "/log")->body;  // every attempt's, in order
  EXPECT_NE(log.find("attempt 1 started"), std::string::npos) << log;
  EXPECT_NE(log.find("attempt 2 started"), std::string::npos) << log;
  EXPECT_NE(log.find(":" + std::to_string(survivor.pid()) + ":"), std::string::npos)
      << "attempt 2 ran in the survivor:\n"
      << log;

  // A cancel posted to API B stops a job that API A queued and the surviving worker runs.
  const std::string long_job = post_job(a, box_scene(3, 60000, {1, 0.5, 0}, 2));
  ASSERT_TRUE(eventually([&] { return get_job(a, long_job).value("status", "") == "running"; },
                         std::chrono::seconds(30)));
  auto r = b.Post("/v1/jobs/" + long_job + "/cancel");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 202) << r->body;
  ASSERT_TRUE(eventually([&] { return get_job(a, long_job).value("status", "") == "canceled"; },
                         std::chrono::seconds(20)))
      << get_job(a, long_job).dump();
  EXPECT_LT(get_job(a, long_job)["progress"].value("step", 60000), 60000);
}

TEST(PgManyProcesses, WhileTheDatabaseRestartsTheApiAnswers503WithRetryAfterAndNoAcceptedJobIsLost) {
  Database db;
  TempDir data;
  LiveServer api(data.path(), {"--store", db.url, "--workers", "0"});
  LiveWorker worker(db.url, data.path(), {"--workers", "2"});
  std::atomic<bool> submitting{true};
  std::atomic<int> refused{0}, refused_with_retry_after{0};
  std::mutex mutex;
  std::vector<std::string> accepted;
  std::thread load([&] {
    auto c = api.client();
    while (submitting) {
      int status = 0;
      bool retry_after = false;
      const std::string id = post_job(c, box_scene(1, 1), &status, &retry_after);
      if (!id.empty()) {
        std::lock_guard lock(mutex);
        accepted.push_back(id);
      } else if (status == 503) {
        ++refused;
        refused_with_retry_after += retry_after;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  auto accepted_count = [&] {
    std::lock_guard lock(mutex);
    return accepted.size();
  };
  ASSERT_TRUE(eventually([&] { return accepted_count() >= 10; }, std::chrono::seconds(30)));
  db.cluster.stop();
  EXPECT_TRUE(eventually([&] { return refused >= 3; }, std::chrono::seconds(30)))
      << "503s while the database is away";
  db.cluster.start();
  const std::size_t before = accepted_count();
  EXPECT_TRUE(eventually([&] { return accepted_count() >= before + 10; }, std::chrono::seconds(30)))
      << "the API recovers by itself";
  submitting = false;
  load.join();
  EXPECT_EQ(refused_with_retry_after.load(), refused.load()) << "every 503 says when to retry";
  std::string id_list;  // as a PostgreSQL array literal
  for (const std::string& id : accepted) id_list += (id_list.empty() ? "'{" : ",") + id;
  id_list += "}'";
  ASSERT_TRUE(eventually(
      [&] {
        return db.count("status = 'succeeded' AND id = ANY(" + id_list + ")") ==
               static_cast<std::int64_t>(accepted.size());
      },
      std::chrono::seconds(60)))
      << db.count("status = 'succeeded' AND id = ANY(" + id_list + ")") << " of " << accepted.size()
      << " accepted jobs succeeded";
  auto c = api.client();
  auto r = c.Get("/v1/jobs?limit=1");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
}

}  // namespace
}  // namespace stoss::test
