// The job store contract, for the SQLite and the PostgreSQL store alike: the system shall keep every
// accepted job, hand each queued job to exactly one worker, honour leases, and migrate its own schema.
#include <gtest/gtest.h>

#include <atomic>
#include <set>
#include <thread>

#include "server/common/sha256.hpp"
#include "server/jobs/store/pg.hpp"
#include "server/jobs/store/pg_store.hpp"
#include "server/jobs/store/sqlite.hpp"
#include "server/jobs/store/sqlite_store.hpp"
#include "tests/server/live_server.hpp"
#include "tests/server/pg_cluster.hpp"

namespace stoss::server::jobs {
namespace {

using Outcome = CreateResult::Outcome;

NewJob new_job(const std::string& name, std::optional<std::string> key = std::nullopt) {
  NewJob job;
  job.idempotency_key = std::move(key);
  job.scene = {{"name", name}};
  job.body_hash = sha256_hex(job.scene.dump());
  job.effects = {"inertia", "elasticity"};
  job.progress = {0, 30, 0.0, 0.3, std::nullopt};
  return job;
}

/// new_job whose scene asks for `ranks` MPI ranks (solver.ranks).
NewJob new_job_on_ranks(const std::string& name, int ranks) {
  NewJob job = new_job(name);
  job.scene["solver"] = {{"ranks", ranks}};
  job.body_hash = sha256_hex(job.scene.dump());
  return job;
}

using test::Backend;

std::string backend_name(const ::testing::TestParamInfo<Backend>& info) {
  return test::to_string(info.param);
}

/// Every test of this fixture runs against both stores.
class StoreTest : public ::testing::TestWithParam<Backend> {
 protected:
  ManualClock clock;
  test::StoreUnderTest backing{GetParam(), clock};
  JobStore& store = backing.store();

  Job create(const std::string& name) { return *store.create(new_job(name), 1000).job; }
};

INSTANTIATE_TEST_SUITE_P(BothStores, StoreTest, ::testing::Values(Backend::sqlite, Backend::postgresql),
                         backend_name);

TEST_P(StoreTest, CreatesAQueuedJobAndReadsItBack) {
  const CreateResult r = store.create(new_job("a"), 10);
  ASSERT_EQ(r.outcome, Outcome::created);
  const Job job = *store.get(r.job->id);
  EXPECT_EQ(job.status, Status::queued);
  EXPECT_EQ(job.created, clock.now());
  EXPECT_EQ(job.attempt, 0);
  EXPECT_EQ(job.effects, (std::vector<std::string>{"inertia", "elasticity"}));
  EXPECT_EQ(job.progress.steps, 30);
  EXPECT_DOUBLE_EQ(job.progress.end, 0.3);
  EXPECT_FALSE(job.started);
}

TEST_P(StoreTest, KeepsTheKindAndTheStudyParameters) {
  EXPECT_EQ(create("a").kind, Kind::simulation);
  NewJob study = new_job("s");
  study.kind = Kind::study;
  study.study = nlohmann::json{{"steps", {0.04, 0.02}}, {"schemes", {"midpoint"}}, {"reference_step", 0.001}};
  const JobId id = store.create(study, 10).job->id;
  const Job read = *store.get(id);
  EXPECT_EQ(read.kind, Kind::study);
  EXPECT_EQ(read.study, study.study);
  store.claim("w", 10'000, 1);  // the older simulation "a"
  const Job claimed = *store.claim("w", 10'000, 1);
  EXPECT_EQ(claimed.kind, Kind::study);
  EXPECT_EQ((*claimed.study)["schemes"][0], "midpoint");
  EXPECT_EQ(claimed.scene["name"], "s");
}

TEST_P(StoreTest, UnknownIdIsAbsent) {
  EXPECT_FALSE(store.get(JobId::random()));
}

TEST_P(StoreTest, SameIdempotencyKeyAndBodyReturnsTheOriginalJob) {
  const Job first = *store.create(new_job("a", "key-1"), 10).job;
  const CreateResult again = store.create(new_job("a", "key-1"), 10);
  EXPECT_EQ(again.outcome, Outcome::existing);
  EXPECT_EQ(again.job->id, first.id);
  const CreateResult other = store.create(new_job("b", "key-1"), 10);
  EXPECT_EQ(other.outcome, Outcome::key_conflict);
  EXPECT_EQ(store.list(std::nullopt, 10, std::nullopt).jobs.size(), 1u);
}

TEST_P(StoreTest, RefusesWhenTheQueueIsFull) {
  create("a");
  create("b");
  EXPECT_EQ(store.create(new_job("c"), 2).outcome, Outcome::queue_full);
  store.claim("w", 10'000, 1);  // a running job does not count as queued
  EXPECT_EQ(store.create(new_job("c"), 2).outcome, Outcome::created);
}

TEST_P(StoreTest, ListsNewestFirstInPagesAndByStatus) {
  std::vector<JobId> ids;
  for (int i = 0; i < 5; ++i) ids.push_back(create(std::string("job").append(std::to_string(i))).id);
  Page first = store.list(std::nullopt, 2, std::nullopt);
  ASSERT_EQ(first.jobs.size(), 2u);
  EXPECT_EQ(first.jobs[0].id, ids[4]);
  EXPECT_EQ(first.jobs[1].id, ids[3]);
  ASSERT_TRUE(first.next_cursor);
  Page second = store.list(std::nullopt, 2, first.next_cursor);
  EXPECT_EQ(second.jobs[0].id, ids[2]);
  Page last = store.list(std::nullopt, 2, second.next_cursor);
  ASSERT_EQ(last.jobs.size(), 1u);
  EXPECT_EQ(last.jobs[0].id, ids[0]);
  EXPECT_FALSE(last.next_cursor);
  store.claim("w", 10'000, 1);
  Page running = store.list(Status::running, 10, std::nullopt);
  ASSERT_EQ(running.jobs.size(), 1u);
  EXPECT_EQ(running.jobs[0].id, ids[0]);
  EXPECT_FALSE(running.next_cursor);
}

TEST_P(StoreTest, ClaimsOldestFirstWithALeaseAndTheScene) {
  const Job a = create("a");
  create("b");
  const Job claimed = *store.claim("worker-1", 10'000, 1);
  EXPECT_EQ(claimed.id, a.id);
  EXPECT_EQ(claimed.status, Status::running);
  EXPECT_EQ(claimed.attempt, 1);
  EXPECT_EQ(claimed.worker, "worker-1");
  EXPECT_EQ(claimed.lease_expires, clock.now() + 10'000);
  EXPECT_EQ(claimed.scene["name"], "a");
  EXPECT_TRUE(store.claim("worker-2", 10'000, 1));
  EXPECT_FALSE(store.claim("worker-3", 10'000, 1));
}

// Issue 27 §5: a job keeps the ranks its scene asks for (1 when it does not say), and a claim within fewer
// ranks leaves it queued, untouched, for a worker that has them.
TEST_P(StoreTest, AJobAskingForMoreRanksStaysQueuedUntilAClaimWithThatManyTakesIt) {
  const Job big = *store.create(new_job_on_ranks("big", 2), 10).job;
  EXPECT_EQ(big.ranks, 2);
  const Job plain = create("plain");
  EXPECT_EQ(plain.ranks, 1) << "a scene without solver.ranks asks for one rank";
  EXPECT_EQ(store.claim("one-rank worker", 10'000, 1)->id, plain.id);
  EXPECT_FALSE(store.claim("one-rank worker", 10'000, 1));
  const Job waiting = *store.get(big.id);
  EXPECT_EQ(waiting.status, Status::queued);
  EXPECT_EQ(waiting.attempt, 0);
  EXPECT_EQ(waiting.ranks, 2);
  EXPECT_EQ(store.list(Status::queued, 10, std::nullopt).jobs.at(0).ranks, 2);
  const Job claimed = *store.claim("two-rank worker", 10'000, 2);
  EXPECT_EQ(claimed.id, big.id);
  EXPECT_EQ(claimed.ranks, 2);
  EXPECT_EQ(claimed.worker, "two-rank worker");
  EXPECT_EQ(claimed.scene["solver"]["ranks"], 2);
}

// Among the jobs within a claim's ranks the oldest goes first, a smaller job included; the ones above wait.
TEST_P(StoreTest, AClaimTakesTheOldestJobWithinItsRanks) {
  const JobId two = store.create(new_job_on_ranks("two", 2), 10).job->id;
  const JobId a = create("a").id;
  const JobId three = store.create(new_job_on_ranks("three", 3), 10).job->id;
  const JobId b = create("b").id;
  EXPECT_EQ(store.claim("w1", 10'000, 1)->id, a) << "the older two-rank job is skipped";
  EXPECT_EQ(store.claim("w4", 10'000, 4)->id, two) << "the oldest job within 4 ranks, not the biggest";
  EXPECT_EQ(store.claim("w2", 10'000, 2)->id, b) << "the older three-rank job is skipped";
  EXPECT_FALSE(store.claim("w2", 10'000, 2));
  EXPECT_EQ(store.claim("w3", 10'000, 3)->id, three);
}

TEST_P(StoreTest, OnlyTheLeaseHolderRenewsReportsAndFinishes) {
  const JobId id = create("a").id;
  const Claim w1 = claim_of(*store.claim("w1", 10'000, 1)), w2{id, "w2", 1};
  clock.advance(5'000);
  EXPECT_EQ(store.renew(w1, 10'000), Lease::held);
  EXPECT_EQ(store.get(id)->lease_expires, clock.now() + 10'000);
  EXPECT_EQ(store.renew(w2, 10'000), Lease::lost);
  EXPECT_TRUE(store.progress(w1, {12, 30, 0.12, 0.3, 1.5}));
  EXPECT_FALSE(store.progress(w2, {13, 30, 0.13, 0.3, 1.4}));
  EXPECT_EQ(store.get(id)->progress.step, 12);
  EXPECT_DOUBLE_EQ(*store.get(id)->progress.eta_seconds, 1.5);
  EXPECT_FALSE(store.finish(w2, {Status::succeeded, nlohmann::json{{"steps", 30}}, std::nullopt}));
  EXPECT_TRUE(store.finish(w1, {Status::succeeded, nlohmann::json{{"steps", 30}}, std::nullopt}));
  const Job done = *store.get(id);
  EXPECT_EQ(done.status, Status::succeeded);
  EXPECT_EQ((*done.summary)["steps"], 30);
  EXPECT_EQ(done.finished, clock.now());
  EXPECT_EQ(done.result_attempt, 1);  // the reporting attempt's folder is published
  EXPECT_EQ(store.renew(w1, 10'000), Lease::lost);
}

// Issue 20: an attempt that lost its lease changes nothing, even when the same worker name claims the job
// again; the attempt that holds the lease may publish an earlier attempt's completed run.
TEST_P(StoreTest, AnAttemptThatLostItsLeaseIsFencedOutByItsAttemptNumber) {
  const JobId id = create("a").id;
  const Claim first = claim_of(*store.claim("w", 1'000, 1));
  clock.advance(1'001);
  ASSERT_EQ(store.expired(clock.now()).size(), 1u);
  EXPECT_EQ(store.expired(clock.now())[0].attempt, 1);
  EXPECT_EQ(store.expired(clock.now())[0].worker, "w");
  ASSERT_EQ(store.requeue_expired(clock.now(), 3).requeued, 1);
  EXPECT_TRUE(store.expired(clock.now()).empty());
  const Claim second = claim_of(*store.claim("w", 1'000, 1));  // the same name, attempt 2
  ASSERT_EQ(second.attempt, 2);
  EXPECT_EQ(store.renew(first, 1'000), Lease::lost);
  EXPECT_FALSE(store.progress(first, {5, 30, 0.05, 0.3, std::nullopt}));
  EXPECT_FALSE(store.release(first));
  EXPECT_FALSE(store.finish(first, {Status::failed, std::nullopt, "cannot open result.h5.partial"}));
  EXPECT_EQ(store.get(id)->status, Status::running);
  EXPECT_FALSE(store.get(id)->result_attempt);
  const jobs::Outcome adopted{Status::succeeded, nlohmann::json{{"steps", 30}}, std::nullopt, 1};
  EXPECT_TRUE(store.finish(second, adopted));
  const Job done = *store.get(id);
  EXPECT_EQ(done.status, Status::succeeded);
  EXPECT_EQ(done.attempt, 2);
  EXPECT_EQ(done.result_attempt, 1);
  EXPECT_FALSE(store.finish(first, adopted)) << "published once";
  EXPECT_EQ(store.list(std::nullopt, 10, std::nullopt).jobs.at(0).result_attempt, 1);
}

TEST_P(StoreTest, CancelStopsAQueuedJobAtOnceAndFlagsARunningOne) {
  const JobId queued = create("q").id;
  const JobId running = create("r").id;
  ASSERT_EQ(store.claim("w", 10'000, 1)->id, queued);  // oldest first: claim the first, requeue trick below
  // Put the first back so that `queued` is queued and `running` runs.
  store.release({queued, "w", 1});
  store.request_cancel(queued);
  ASSERT_EQ(store.claim("w", 10'000, 1)->id, running);

  EXPECT_EQ(store.get(queued)->status, Status::canceled);
  EXPECT_EQ(store.get(queued)->attempt, 0);  // release does not count the attempt
  const CancelResult r = store.request_cancel(running);
  EXPECT_EQ(r.outcome, CancelResult::Outcome::requested);
  EXPECT_EQ(r.job->status, Status::running);
  EXPECT_TRUE(r.job->cancel_requested);
  EXPECT_EQ(store.renew({running, "w", 1}, 10'000), Lease::cancel_requested);
  EXPECT_EQ(store.request_cancel(queued).outcome, CancelResult::Outcome::canceled);  // again: a no-op
  store.finish({running, "w", 1}, {Status::succeeded, std::nullopt, std::nullopt});
  EXPECT_EQ(store.request_cancel(running).outcome, CancelResult::Outcome::already_done);
  EXPECT_EQ(store.request_cancel(JobId::random()).outcome, CancelResult::Outcome::not_found);
}

TEST_P(StoreTest, RemovesOnlyFinishedJobs) {
  const JobId id = create("a").id;
  EXPECT_EQ(store.remove(id), RemoveOutcome::not_finished);
  store.request_cancel(id);
  EXPECT_EQ(store.remove(id), RemoveOutcome::removed);
  EXPECT_FALSE(store.get(id));
  EXPECT_EQ(store.remove(id), RemoveOutcome::not_found);
}

TEST_P(StoreTest, CountsJobsByStatus) {
  create("a");
  create("b");
  store.claim("w", 10'000, 1);
  auto counts = store.count_by_status();
  EXPECT_EQ(counts[Status::queued], 1);
  EXPECT_EQ(counts[Status::running], 1);
  EXPECT_EQ(counts[Status::failed], 0);
  EXPECT_EQ(counts.size(), 5u);
}

TEST_P(StoreTest, KeepsJobsAcrossReopening) {
  const JobId id = create("a").id;
  const auto reopened = backing.open_again();
  EXPECT_EQ(reopened->get(id)->status, Status::queued);
}

TEST(SqliteStore, IsInWalModeAtTheLatestSchemaVersion) {
  test::TempDir dir;
  ManualClock clock;
  SqliteStore store{dir.path() / "jobs.db", clock};
  EXPECT_EQ(store.schema_version(), SqliteStore::latest_schema_version());
  sqlite::Connection c(dir.path() / "jobs.db", 1000);
  sqlite::Statement s(c, "PRAGMA journal_mode");
  ASSERT_TRUE(s.step());
  EXPECT_EQ(s.text(0), "wal");
}

TEST(StoreMigration, MigratesAVersionOneDatabase) {
  test::TempDir dir;
  ManualClock clock;
  {
    sqlite::Connection c(dir.path() / "jobs.db", 1000);
    // What the first release created: version 1 only, one job in it.
    c.exec(
        "CREATE TABLE schema_version (version INTEGER PRIMARY KEY, applied_ms INTEGER NOT NULL);"
        "INSERT INTO schema_version VALUES (1, 0);"
        "CREATE TABLE jobs (seq INTEGER PRIMARY KEY AUTOINCREMENT, id TEXT NOT NULL UNIQUE, status TEXT NOT "
        "NULL,"
        " created_ms INTEGER NOT NULL, started_ms INTEGER, finished_ms INTEGER, attempt INTEGER NOT NULL "
        "DEFAULT 0,"
        " worker TEXT, lease_expires_ms INTEGER, cancel_requested INTEGER NOT NULL DEFAULT 0,"
        " idempotency_key TEXT UNIQUE, body_hash TEXT NOT NULL, scene TEXT NOT NULL, effects TEXT NOT NULL,"
        " progress_step INTEGER NOT NULL DEFAULT 0, progress_steps INTEGER NOT NULL DEFAULT 0,"
        " progress_time REAL NOT NULL DEFAULT 0, progress_end REAL NOT NULL DEFAULT 0, progress_eta REAL,"
        " summary TEXT, error TEXT);"
        "INSERT INTO jobs (id, status, created_ms, body_hash, scene, effects)"
        " VALUES ('0123456789abcdef0123456789abcdef', 'queued', 0, 'h', '{}', '[]');");
  }
  SqliteStore store(dir.path() / "jobs.db", clock);
  EXPECT_EQ(store.schema_version(), SqliteStore::latest_schema_version());
  const auto old = store.get(*JobId::parse("0123456789abcdef0123456789abcdef"));
  ASSERT_TRUE(old);
  EXPECT_EQ(old->kind, Kind::simulation);  // every job from before study jobs is a simulation
  EXPECT_FALSE(old->study);
  EXPECT_EQ(old->ranks, 1);  // every job from before solver.ranks asks for one rank
  EXPECT_EQ(store.claim("w", 10'000, 1)->id, old->id);
  sqlite::Connection c(dir.path() / "jobs.db", 1000);
  sqlite::Statement index(
      c, "SELECT count(*) FROM sqlite_master WHERE type = 'index' AND name = 'jobs_by_lease'");
  index.step();
  EXPECT_EQ(index.int64(0), 1);
}

TEST(StoreMigration, RefusesADatabaseFromANewerProgram) {
  test::TempDir dir;
  ManualClock clock;
  { SqliteStore store(dir.path() / "jobs.db", clock); }
  {
    sqlite::Connection c(dir.path() / "jobs.db", 1000);
    c.exec("INSERT INTO schema_version VALUES (999, 0)");
  }
  try {
    SqliteStore store(dir.path() / "jobs.db", clock);
    FAIL() << "opened a database of schema version 999";
  } catch (const sqlite::Error& e) {
    EXPECT_NE(std::string(e.what()).find("schema version 999 is newer"), std::string::npos) << e.what();
  }
}

class StoreConcurrency : public ::testing::TestWithParam<Backend> {};
INSTANTIATE_TEST_SUITE_P(BothStores, StoreConcurrency,
                         ::testing::Values(Backend::sqlite, Backend::postgresql), backend_name);

TEST_P(StoreConcurrency, EveryQueuedJobIsClaimedExactlyOnce) {
  SystemClock clock;
  test::StoreUnderTest backing(GetParam(), clock);
  JobStore& store = backing.store();
  constexpr int jobs = 60, threads = 6;
  std::vector<std::thread> creators;
  for (int t = 0; t < threads; ++t)
    creators.emplace_back([&, t] {
      for (int i = 0; i < jobs / threads; ++i)
        store.create(new_job(std::to_string(t) + "/" + std::to_string(i)), 1000);
    });
  for (auto& t : creators) t.join();
  std::mutex mutex;
  std::multiset<std::string> claimed;
  std::vector<std::thread> workers;
  for (int t = 0; t < threads; ++t)
    workers.emplace_back([&, t] {
      while (auto job = store.claim(std::string("w").append(std::to_string(t)), 10'000, 1)) {
        std::lock_guard lock(mutex);
        claimed.insert(job->id.str());
      }
    });
  for (auto& t : workers) t.join();
  EXPECT_EQ(claimed.size(), static_cast<std::size_t>(jobs));
  EXPECT_EQ(std::set<std::string>(claimed.begin(), claimed.end()).size(), claimed.size());
}

TEST(PgStoreMigration, CreatesTheLatestSchemaOnceWhenManyProcessesStartTogether) {
  test::PgCluster& cluster = test::PgCluster::shared();
  const std::string db = cluster.create_database();
  ManualClock clock;
  std::vector<std::thread> starts;
  std::atomic<int> opened{0};
  for (int i = 0; i < 4; ++i)
    starts.emplace_back([&] {
      PgStore store(cluster.url(db), clock);
      opened += store.schema_version() == PgStore::latest_schema_version();
    });
  for (auto& t : starts) t.join();
  EXPECT_EQ(opened, 4);
  pg::Connection c(cluster.url(db));
  EXPECT_EQ(c.exec("SELECT count(*) FROM stoss_schema_version").int64(0, 0),
            PgStore::latest_schema_version());
  cluster.drop_database(db);
}

// What the previous release (schema version 2) left, one queued job in it: migration 3 adds `ranks`, 1 for
// that job, and a one-rank worker claims it.
TEST(PgStoreMigration, MigratesAVersionTwoDatabaseWhoseJobsAskForOneRank) {
  test::PgCluster& cluster = test::PgCluster::shared();
  const std::string db = cluster.create_database();
  ManualClock clock;
  pg::Connection(cluster.url(db))
      .exec(
          "CREATE TABLE stoss_schema_version (version INTEGER PRIMARY KEY, applied_ms BIGINT NOT NULL);"
          "INSERT INTO stoss_schema_version VALUES (1, 0), (2, 0);"
          "CREATE TABLE stoss_jobs (seq BIGSERIAL PRIMARY KEY, id TEXT NOT NULL UNIQUE,"
          " kind TEXT NOT NULL DEFAULT 'simulation', status TEXT NOT NULL, created_ms BIGINT NOT NULL,"
          " started_ms BIGINT, finished_ms BIGINT, attempt INTEGER NOT NULL DEFAULT 0, worker TEXT,"
          " lease_expires_ms BIGINT, cancel_requested BOOLEAN NOT NULL DEFAULT false,"
          " idempotency_key TEXT UNIQUE, body_hash TEXT NOT NULL, scene TEXT NOT NULL, name TEXT, study TEXT,"
          " effects TEXT NOT NULL, progress_step INTEGER NOT NULL DEFAULT 0,"
          " progress_steps INTEGER NOT NULL DEFAULT 0, progress_time DOUBLE PRECISION NOT NULL DEFAULT 0,"
          " progress_end DOUBLE PRECISION NOT NULL DEFAULT 0, progress_eta DOUBLE PRECISION, summary TEXT,"
          " error TEXT, result_attempt INTEGER);"
          "INSERT INTO stoss_jobs (id, status, created_ms, body_hash, scene, effects)"
          " VALUES ('0123456789abcdef0123456789abcdef', 'queued', 0, 'h', '{}', '[]');");
  {
    PgStore store(cluster.url(db), clock);
    EXPECT_EQ(store.schema_version(), PgStore::latest_schema_version());
    const auto old = store.get(*JobId::parse("0123456789abcdef0123456789abcdef"));
    ASSERT_TRUE(old);
    EXPECT_EQ(old->ranks, 1);
    EXPECT_EQ(store.claim("w", 10'000, 1)->id, old->id);
  }
  cluster.drop_database(db);
}

TEST(PgStoreMigration, RefusesADatabaseFromANewerProgram) {
  test::PgCluster& cluster = test::PgCluster::shared();
  const std::string db = cluster.create_database();
  ManualClock clock;
  { PgStore store(cluster.url(db), clock); }
  pg::Connection(cluster.url(db)).exec("INSERT INTO stoss_schema_version VALUES (999, 0)");
  try {
    PgStore store(cluster.url(db), clock);
    ADD_FAILURE() << "opened a database of schema version 999";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("database schema version 999 is newer than this program's (" +
                                         std::to_string(PgStore::latest_schema_version()) + ")"),
              std::string::npos)
        << e.what();
  }
  cluster.drop_database(db);
}

TEST(PgStoreErrors, WrongCredentialsAndAnAbsentServerAreUnavailableWithLibpqsReason) {
  test::PgCluster& cluster = test::PgCluster::shared();
  ManualClock clock;
  const std::string wrong =
      "postgresql://stoss:wrong@127.0.0.1:" + std::to_string(cluster.port()) + "/postgres";
  try {
    PgStore store(wrong, clock);
    ADD_FAILURE() << "connected with a wrong password";
  } catch (const StoreUnavailable& e) {
    EXPECT_NE(std::string(e.what()).find("password authentication failed for user \"stoss\""),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(pg::redacted(wrong),
            "postgresql://stoss:***@127.0.0.1:" + std::to_string(cluster.port()) + "/postgres");
  EXPECT_THROW(pg::check_url("postgresql://stoss@127.0.0.1:99999/db"), StoreError);
}

}  // namespace
}  // namespace stoss::server::jobs
