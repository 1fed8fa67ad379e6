#pragma once
/// @file WorkerPool: N threads that claim queued jobs, hold their leases while an Executor runs them,
/// and report how each run ended.

#include <atomic>
#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "server/jobs/running/executor.hpp"
#include "server/jobs/running/periodic.hpp"
#include "server/jobs/store/store.hpp"

namespace stoss::server::jobs {

struct WorkerPoolOptions {
  int workers = 2;        ///< concurrent runs (0: this process only queues)
  Millis lease = 10'000;  ///< a claim holds the job this long unless renewed
  Millis renew_every = 2'000;
  /// An idle worker looks for work this often even when not notified (a store that announces queued jobs
  /// itself, PostgreSQL's NOTIFY, needs only a rare fallback: pool_options_for).
  Millis idle_poll = 500;
  /// --ranks-per-job: the MPI ranks one job may use here; a worker claims only jobs asking for at most this.
  int ranks_per_job = 1;
};

class WorkerPool {
 public:
  WorkerPool(JobStore& store, Executor& executor, WorkerPoolOptions options);
  ~WorkerPool() { stop(); }
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  /// Starts the worker threads and the lease keeper.
  void start();
  /// Stops claiming, stops the running jobs within a step, gives them back to the queue (they run
  /// again on the next start), and joins every thread.
  void stop();
  /// Wakes idle workers: a job was queued.
  void notify();
  /// Stops job `id` within a step if this pool is running it; true if it was.
  bool cancel(const JobId& id);
  /// Number of jobs this pool is running now.
  int running() const;
  /// This process's worker-name prefix (host, pid, random suffix).
  const std::string& name() const { return name_; }

 private:
  /// Why a running job's cancel flag was set.
  enum class Stop { none, user, shutdown, lease_lost };
  struct Running {
    explicit Running(Claim claim) : claim(std::move(claim)) {}
    Claim claim;
    std::atomic<bool> cancel{false};
    std::atomic<Stop> why{Stop::none};
    void stop(Stop reason);
  };

  void work(int index);
  void run_claimed(const Job& job);
  /// Reports how the run ended while the claim holds; retries while the store is away (a completed run is
  /// reported when the database is back), until the pool stops.
  void report(const Running& running, const Outcome& outcome);
  bool stopping() const;
  void renew_leases();
  std::optional<Job> claim(const std::string& worker);

  JobStore& store_;
  Executor& executor_;
  WorkerPoolOptions options_;
  std::string name_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::uint64_t wakes_ = 0;  ///< notify() calls so far: a wake during a claim is not lost
  std::map<JobId, std::shared_ptr<Running>> running_;
  std::vector<std::thread> threads_;
  std::unique_ptr<Periodic> lease_keeper_;
};

}  // namespace stoss::server::jobs
