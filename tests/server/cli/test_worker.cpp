// `--store` and `stoss worker` at start-up: the system shall refuse a malformed store URL, an unreachable
// database, wrong credentials and a newer schema with a message naming the cause and exit code 2, and
// shall create nothing (no data directory) when it refuses.
#include <gtest/gtest.h>

#include <condition_variable>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <vector>

#include "server/cli/worker.hpp"
#include "server/jobs/store/pg.hpp"
#include "server/jobs/store/pg_store.hpp"
#include "tests/server/live_server.hpp"
#include "tests/server/pg_cluster.hpp"

namespace stoss::test {
namespace {

namespace fs = std::filesystem;

std::string with_port(const std::string& user_password, int port, const std::string& db) {
  return "postgresql://" + user_password + "@127.0.0.1:" + std::to_string(port) + "/" + db;
}

TEST(PgCli, AMalformedStoreIsRefusedWithTheRuleAndExit2) {
  TempDir dir;
  const CommandResult other =
      run_stoss({"serve", "--store", "mysql://x/y", "--data", (dir.path() / "d").string()});
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_NE(other.err.find(
                "--store needs sqlite:PATH or postgresql://USER[:PASSWORD]@HOST:PORT/DB, got 'mysql://x/y'"),
            std::string::npos)
      << other.err;
  const CommandResult port = run_stoss({"worker", "--store", "postgresql://stoss:pw@127.0.0.1:99999/db"});
  EXPECT_EQ(port.exit_code, 2);
  EXPECT_NE(port.err.find("the port of a PostgreSQL store URL must be an integer in [1, 65535], got '99999'"),
            std::string::npos)
      << port.err;
  const CommandResult empty = run_stoss({"worker", "--store", "sqlite:"});
  EXPECT_EQ(empty.exit_code, 2);
  EXPECT_NE(empty.err.find("--store sqlite:PATH needs a file name"), std::string::npos) << empty.err;
  EXPECT_FALSE(fs::exists(dir.path() / "d"));
}

TEST(PgCli, AWorkerTakesOnlyTheFlagsThatConcernRunningJobs) {
  const CommandResult listen = run_stoss({"worker", "--listen", "127.0.0.1:0"});
  EXPECT_EQ(listen.exit_code, 2);
  EXPECT_NE(listen.err.find("unknown option '--listen'"), std::string::npos) << listen.err;
  const CommandResult zero = run_stoss({"worker", "--workers", "0"});
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_NE(zero.err.find("--workers needs an integer in [1, 256], got '0'"), std::string::npos) << zero.err;
  const CommandResult help = run_stoss({"worker", "--help"});
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("--store STORE"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("--ranks-per-job N"), std::string::npos) << help.out;
}

// Issue 27 §5: a worker claims only jobs within --ranks-per-job (a runner flag, shared with serve).
TEST(WorkerOptions, RanksPerJobSetsThePoolsClaimBound) {
  EXPECT_EQ(cli::parse_worker_options({"--store", "sqlite:jobs.db"}).pool.ranks_per_job, 1);
  EXPECT_EQ(
      cli::parse_worker_options({"--store", "sqlite:jobs.db", "--ranks-per-job", "16"}).pool.ranks_per_job,
      16);
  EXPECT_THROW(cli::parse_worker_options({"--ranks-per-job", "0"}), cli::UsageError);
  EXPECT_THROW(cli::parse_worker_options({"--max-ranks-per-job", "2"}), cli::UsageError)
      << "serve's, not a worker's";
}

TEST(PgCli, AnUnreachableDatabaseOrWrongCredentialsExit2AndCreateNothing) {
  PgCluster& cluster = PgCluster::shared();
  TempDir dir;
  const fs::path data = dir.path() / "data";
  const std::string wrong = with_port("stoss:not-the-password", cluster.port(), "postgres");
  const CommandResult refused =
      run_stoss({"serve", "--listen", "127.0.0.1:0", "--store", wrong, "--data", data.string()});
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("password authentication failed for user \"stoss\""), std::string::npos)
      << refused.err;
  EXPECT_EQ(refused.err.find("not-the-password"), std::string::npos) << "the password is never printed";
  EXPECT_NE(refused.err.find("stoss:***@127.0.0.1"), std::string::npos) << refused.err;

  // Port 1 (tcpmux) has no listener: the connection is refused.
  const std::string away = with_port("stoss:secret", 1, "postgres");
  const CommandResult unreachable = run_stoss({"worker", "--store", away, "--data", data.string()});
  EXPECT_EQ(unreachable.exit_code, 2);
  EXPECT_NE(unreachable.err.find(
                "cannot open the job store postgresql://stoss:***@127.0.0.1:1/postgres: cannot connect"),
            std::string::npos)
      << unreachable.err;
  EXPECT_FALSE(fs::exists(data)) << "no data directory is created for a store that cannot be opened";
}

TEST(PgCli, ADatabaseOfANewerSchemaIsRefusedAtStartWithExit2) {
  PgCluster& cluster = PgCluster::shared();
  const std::string db = cluster.create_database();
  server::jobs::ManualClock clock;
  { server::jobs::PgStore store(cluster.url(db), clock); }
  server::jobs::pg::Connection(cluster.url(db)).exec("INSERT INTO stoss_schema_version VALUES (7, 0)");
  TempDir dir;
  const CommandResult r = run_stoss({"worker", "--store", cluster.url(db), "--data", dir.path().string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("database schema version 7 is newer than this program's (" +
                       std::to_string(server::jobs::PgStore::latest_schema_version()) + ")"),
            std::string::npos)
      << r.err;
  cluster.drop_database(db);
}

TEST(Worker, RunsTheJobsAnApiOnlyServerQueuesInAnSqliteStoreOnOneHost) {
  TempDir dir;
  const fs::path data = dir.path() / "data";
  LiveServer api(data, {"--workers", "0"});
  auto c = api.client();
  auto r = c.Post("/v1/jobs", box_scene(1, 2).dump(), "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;
  const std::string id = nlohmann::json::parse(r->body)["id"];
  auto status = [&] {
    return nlohmann::json::parse(c.Get("/v1/jobs/" + id)->body)["status"].get<std::string>();
  };
  EXPECT_EQ(status(), "queued") << "an API-only server runs nothing";
  // A worker on the same host shares the API's SQLite file (sqlite:DATA/jobs.db, both defaults).
  LiveWorker worker("sqlite:" + (data / "jobs.db").string(), data, {"--workers", "1"});
  EXPECT_TRUE(eventually([&] { return status() == "succeeded"; }, std::chrono::seconds(60))) << status();
  const std::string log = c.Get("/v1/jobs/" + id + "/log")->body;
  EXPECT_NE(log.find(":" + std::to_string(worker.pid()) + ":"), std::string::npos)
      << "the worker process ran it:\n"
      << log;
}

TEST(PgCli, APasswordFileNamedByPgpassfileSuppliesTheMissingPassword) {
  PgCluster& cluster = PgCluster::shared();
  TempDir dir;
  const fs::path passfile = dir.path() / "pgpass";
  std::ofstream(passfile) << "127.0.0.1:" << cluster.port() << ":*:stoss:secret\n";
  fs::permissions(passfile, fs::perms::owner_read | fs::perms::owner_write);  // libpq ignores a looser file
  const std::string without_password = with_port("stoss", cluster.port(), "postgres");
  server::jobs::ManualClock clock;
  EXPECT_THROW(server::jobs::PgStore(without_password, clock), server::jobs::StoreUnavailable);
  setenv("PGPASSFILE", passfile.c_str(), 1);
  try {
    server::jobs::PgStore store(without_password, clock);
    EXPECT_EQ(store.schema_version(), server::jobs::PgStore::latest_schema_version());
  } catch (const std::exception& e) {
    ADD_FAILURE() << e.what();
  }
  unsetenv("PGPASSFILE");
  EXPECT_NO_THROW(server::jobs::pg::check_url("postgresql://stoss@[::1]:5432/stoss"));
}

TEST(PgNotify, QueuedJobsAndCancelsPostedThroughAnotherConnectionReachTheSubscriber) {
  PgCluster& cluster = PgCluster::shared();
  const std::string db = cluster.create_database();
  server::jobs::SystemClock clock;
  server::jobs::PgStore api(cluster.url(db), clock), worker(cluster.url(db), clock);
  std::mutex mutex;
  std::condition_variable heard;
  int wakes = 0;
  std::vector<std::string> cancels;
  {
    const auto subscription = worker.subscribe({[&] {
                                                  std::lock_guard lock(mutex);
                                                  ++wakes;
                                                  heard.notify_all();
                                                },
                                                [&](const server::jobs::JobId& id) {
                                                  std::lock_guard lock(mutex);
                                                  cancels.push_back(id.str());
                                                  heard.notify_all();
                                                }});
    // The listener connects in the background: queue jobs until one is heard (each create notifies).
    for (int i = 0; i < 50; ++i) {
      server::jobs::NewJob job;
      job.scene = {{"name", "n" + std::to_string(i)}};
      job.body_hash = "h";
      ASSERT_EQ(api.create(job, 100).outcome, server::jobs::CreateResult::Outcome::created);
      std::unique_lock lock(mutex);
      if (heard.wait_for(lock, std::chrono::milliseconds(200), [&] { return wakes > 0; })) break;
    }
    EXPECT_GT(wakes, 0) << "NOTIFY stoss_jobs reached the LISTEN connection";
    const auto running = worker.claim("w", 10'000, 1);
    ASSERT_TRUE(running);
    EXPECT_EQ(api.request_cancel(running->id).outcome, server::jobs::CancelResult::Outcome::requested);
    std::unique_lock lock(mutex);
    heard.wait_for(lock, std::chrono::seconds(20), [&] { return !cancels.empty(); });
    EXPECT_EQ(cancels, std::vector<std::string>{running->id.str()}) << "NOTIFY stoss_cancel names the job";
  }
  cluster.drop_database(db);
}

}  // namespace
}  // namespace stoss::test
