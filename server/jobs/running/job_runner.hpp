#pragma once
/// @file What runs jobs in a process, the same in `stoss serve` and `stoss worker`: the job store, one
/// process per job (`stoss run-job`), the worker pool woken by the store's events (jobs queued and cancels
/// posted through other processes), and the rescuer of expired leases.

#include <filesystem>
#include <memory>

#include "server/jobs/running/periodic.hpp"
#include "server/jobs/running/process_executor.hpp"
#include "server/jobs/running/rescuer.hpp"
#include "server/jobs/running/worker_pool.hpp"
#include "server/jobs/store/open_store.hpp"

namespace stoss::server::jobs {

struct JobRunnerOptions {
  std::filesystem::path data;  ///< results and logs: DIR/jobs/<id>/
  StoreLocation store;
  ProcessLimits limits;  ///< of each job's process
  WorkerPoolOptions pool;
  int max_attempts = 3;  ///< runs before an expired lease fails a job
};

/// How often an idle worker polls a store that also wakes it (PostgreSQL's LISTEN/NOTIFY): only to cover
/// a lost notification.
inline constexpr Millis notify_fallback_poll = 30'000;

/// `pool` with the idle poll the store needs: notify_fallback_poll for PostgreSQL, unchanged for SQLite.
WorkerPoolOptions pool_options_for(const StoreLocation& location, WorkerPoolOptions pool);

/// Threads for each job process's element loops when `workers` jobs run at once on `cores` cores:
/// an equal share, at least one (results do not depend on it: core/fem/assembly.hpp).
int element_threads_per_job(int workers, unsigned cores);

class JobRunner {
 public:
  /// Opens the store (throws StoreOpenError), creates DIR/jobs and subscribes to the store's events.
  /// Unless the operator set STOSS_THREADS, sets it for the job processes to element_threads_per_job,
  /// so that concurrent jobs share the cores instead of each taking all of them.
  JobRunner(const JobRunnerOptions& options, const Clock& clock);
  ~JobRunner() { stop(); }
  JobRunner(const JobRunner&) = delete;
  JobRunner& operator=(const JobRunner&) = delete;

  JobStore& store() { return *store_; }
  WorkerPool& pool() { return pool_; }
  const JobFiles& files() const { return files_; }

  /// Requeues the jobs of dead processes whose lease already ran out, then starts the rescuer's period
  /// (the lease renewal interval) and the workers.
  void start();
  /// Stops the rescuer and the workers (running jobs go back to the queue); idempotent.
  void stop();

 private:
  std::unique_ptr<JobStore> store_;
  JobFiles files_;
  ProcessExecutor executor_;
  WorkerPool pool_;
  std::unique_ptr<Subscription> subscription_;
  Rescuer rescuer_;
  std::chrono::milliseconds rescue_every_;
  std::unique_ptr<Periodic> rescuing_;
};

}  // namespace stoss::server::jobs
