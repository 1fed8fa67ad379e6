// The worker pool with a scripted executor: the system shall run claimed jobs, stop a running job when
// asked, give running jobs back to the queue on shutdown, and report nothing once a lease is lost.
// Synchronisation is by signals from the executor, not by sleeps.
#include <gtest/gtest.h>

#include <condition_variable>
#include <future>
#include <mutex>

#include "server/jobs/running/job_runner.hpp"
#include "server/jobs/running/worker_pool.hpp"
#include "server/jobs/store/sqlite_store.hpp"
#include "tests/server/live_server.hpp"

namespace stoss::server::jobs {
namespace {

/// An executor that announces each run and then waits until released or canceled.
class ScriptedExecutor : public Executor {
 public:
  Outcome run(const Job& job, const std::atomic<bool>& cancel, const ProgressSink& progress) override {
    progress({1, 10, 0.1, 1.0, 9.0});
    {
      std::unique_lock lock(mutex_);
      started_.push_back(job.id);
      changed_.notify_all();
      changed_.wait(lock, [&] { return release_ || cancel.load(); });
    }
    if (cancel) return {Status::canceled, nlohmann::json{{"completed", false}}, std::nullopt};
    return {Status::succeeded, nlohmann::json{{"completed", true}}, std::nullopt};
  }
  /// Blocks until `n` runs have started.
  void wait_started(std::size_t n) {
    std::unique_lock lock(mutex_);
    ASSERT_TRUE(changed_.wait_for(lock, std::chrono::seconds(30), [&] { return started_.size() >= n; }));
  }
  void release_all() {
    std::lock_guard lock(mutex_);
    release_ = true;
    changed_.notify_all();
  }
  /// Wakes waiting runs so they see their cancel flag.
  void poke() { changed_.notify_all(); }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<JobId> started_;
  bool release_ = false;
};

class WorkerPoolTest : public ::testing::Test {
 protected:
  test::TempDir dir;
  SystemClock clock;
  SqliteStore store{dir.path() / "jobs.db", clock};
  ScriptedExecutor executor;

  JobId queue_one() { return queue_on_ranks(1); }
  /// A job whose scene asks for `ranks` MPI ranks (solver.ranks).
  JobId queue_on_ranks(int ranks) {
    nlohmann::json scene = {{"name", "x"}, {"solver", {{"ranks", ranks}}}};
    return store.create({std::nullopt, "hash", scene, {}, {}, Kind::simulation, std::nullopt}, 100).job->id;
  }
  Status status(const JobId& id) { return store.get(id)->status; }
  bool reaches(const JobId& id, Status s) {
    return test::eventually([&] { return status(id) == s; }, std::chrono::seconds(30));
  }
};

TEST_F(WorkerPoolTest, RunsAQueuedJobToSuccess) {
  WorkerPool pool(store, executor, {2, 10'000, 2'000, 50});
  pool.start();
  const JobId id = queue_one();
  pool.notify();
  executor.wait_started(1);
  EXPECT_EQ(status(id), Status::running);
  EXPECT_EQ(store.get(id)->progress.step, 1);
  executor.release_all();
  ASSERT_TRUE(reaches(id, Status::succeeded));
  EXPECT_EQ((*store.get(id)->summary)["completed"], true);
}

// Issue 27 §5: a pool claims only jobs within its ranks_per_job (--ranks-per-job); an older, bigger job waits
// for a pool that has the ranks.
TEST_F(WorkerPoolTest, ClaimsOnlyJobsWithinItsRanksPerJob) {
  const JobId big = queue_on_ranks(2);
  const JobId small = queue_one();
  {
    WorkerPool one_rank(store, executor, {1, 10'000, 2'000, 50, 1});
    one_rank.start();
    executor.wait_started(1);
    EXPECT_EQ(status(small), Status::running);
    EXPECT_EQ(status(big), Status::queued);
    executor.release_all();
    ASSERT_TRUE(reaches(small, Status::succeeded));
  }
  EXPECT_EQ(status(big), Status::queued);
  EXPECT_EQ(store.get(big)->attempt, 0);
  WorkerPool two_ranks(store, executor, {1, 10'000, 2'000, 50, 2});
  two_ranks.start();
  ASSERT_TRUE(reaches(big, Status::succeeded));
}

TEST_F(WorkerPoolTest, CancelStopsTheRunningJob) {
  WorkerPool pool(store, executor, {1, 10'000, 2'000, 50});
  pool.start();
  const JobId id = queue_one();
  pool.notify();
  executor.wait_started(1);
  ASSERT_EQ(store.request_cancel(id).outcome, CancelResult::Outcome::requested);
  EXPECT_TRUE(pool.cancel(id));
  executor.poke();
  ASSERT_TRUE(reaches(id, Status::canceled));
  EXPECT_FALSE(pool.cancel(id));
}

TEST_F(WorkerPoolTest, ACancelRequestedInTheStoreReachesTheWorkerThroughTheLeaseRenewal) {
  WorkerPool pool(store, executor, {1, 10'000, 50, 50});  // renew every 50 ms
  pool.start();
  const JobId id = queue_one();
  pool.notify();
  executor.wait_started(1);
  store.request_cancel(id);  // as another server process sharing the database would
  ASSERT_TRUE(test::eventually(
      [&] {
        executor.poke();
        return status(id) == Status::canceled;
      },
      std::chrono::seconds(30)));
}

TEST_F(WorkerPoolTest, ShutdownGivesRunningJobsBackWithoutCountingTheAttempt) {
  const JobId id = queue_one();
  {
    WorkerPool pool(store, executor, {1, 10'000, 2'000, 50});
    pool.start();
    executor.wait_started(1);
    auto stopped = std::async(std::launch::async, [&] { pool.stop(); });
    while (stopped.wait_for(std::chrono::milliseconds(10)) != std::future_status::ready) executor.poke();
  }
  const Job job = *store.get(id);
  EXPECT_EQ(job.status, Status::queued);
  EXPECT_EQ(job.attempt, 0);
}

TEST_F(WorkerPoolTest, AWorkerThatLostItsLeaseReportsNothing) {
  ManualClock manual;
  SqliteStore fake_time_store(dir.path() / "other.db", manual);
  WorkerPool pool(fake_time_store, executor, {1, 10'000, 50, 50});
  nlohmann::json scene = {{"name", "x"}};
  const JobId id =
      fake_time_store.create({std::nullopt, "hash", scene, {}, {}, Kind::simulation, std::nullopt}, 100)
          .job->id;
  pool.start();
  executor.wait_started(1);
  manual.advance(60'000);  // the lease runs out; the rescuer gives the job to someone else
  ASSERT_EQ(fake_time_store.requeue_expired(manual.now(), 3).requeued, 1);
  const Job stolen = *fake_time_store.claim("someone else", 10'000, 1);
  ASSERT_EQ(stolen.id, id);
  // The lease keeper notices within 50 ms and stops the run; the stale outcome is never written.
  ASSERT_TRUE(test::eventually(
      [&] {
        executor.poke();
        return pool.running() == 0;
      },
      std::chrono::seconds(30)));
  const Job job = *fake_time_store.get(id);
  EXPECT_EQ(job.status, Status::running);
  EXPECT_EQ(job.worker, "someone else");
  pool.stop();
}

// Job processes that run at once share the cores for their element loops, at least one thread each.
TEST(JobRunner, ConcurrentJobsShareTheCoresForTheirElementLoops) {
  EXPECT_EQ(element_threads_per_job(2, 2), 1);
  EXPECT_EQ(element_threads_per_job(1, 2), 2);
  EXPECT_EQ(element_threads_per_job(3, 2), 1);
  EXPECT_EQ(element_threads_per_job(2, 8), 4);
  EXPECT_EQ(element_threads_per_job(0, 4), 4);
  EXPECT_EQ(element_threads_per_job(4, 0), 1);  // hardware_concurrency() unknown
}

}  // namespace
}  // namespace stoss::server::jobs
