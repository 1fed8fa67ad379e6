#include "server/jobs/running/job_runner.hpp"

#include <algorithm>
#include <cstdlib>
#include <string>
#include <thread>

namespace stoss::server::jobs {

namespace {

JobFiles prepared_files(const std::filesystem::path& data) {
  std::filesystem::create_directories(data / "jobs");
  return JobFiles(data);
}

/// Called before any thread of the runner exists: setenv is not safe beside other threads' getenv.
JobFiles share_cores_then_prepare(const JobRunnerOptions& options) {
  if (!std::getenv("STOSS_THREADS") && options.pool.workers > 0) {
    const int threads = element_threads_per_job(options.pool.workers, std::thread::hardware_concurrency());
    setenv("STOSS_THREADS", std::to_string(threads).c_str(), 0);  // inherited by every job process
  }
  return prepared_files(options.data);
}

}  // namespace

WorkerPoolOptions pool_options_for(const StoreLocation& location, WorkerPoolOptions pool) {
  if (location.kind == StoreLocation::Kind::postgresql) pool.idle_poll = notify_fallback_poll;
  return pool;
}

int element_threads_per_job(int workers, unsigned cores) {
  return std::max(1, static_cast<int>(cores) / std::max(1, workers));
}

JobRunner::JobRunner(const JobRunnerOptions& options, const Clock& clock)
    : store_(open_store(options.store, clock)),
      files_(share_cores_then_prepare(options)),
      // Each job runs in a process of its own (this binary, `stoss run-job`): a job that crashes or runs
      // over a limit fails alone.
      executor_(files_, options.data, std::filesystem::read_symlink("/proc/self/exe"), options.limits),
      pool_(*store_, executor_, pool_options_for(options.store, options.pool)),
      subscription_(
          store_->subscribe({[this] { pool_.notify(); }, [this](const JobId& id) { pool_.cancel(id); }})),
      rescuer_(*store_, clock, options.max_attempts, files_),
      rescue_every_(options.pool.renew_every) {}

void JobRunner::start() {
  rescuer_.run_once();  // jobs of a dead process whose lease already ran out go back to the queue first
  rescuing_ = std::make_unique<Periodic>("rescuer", rescue_every_, [this] {
    if (rescuer_.run_once().requeued > 0) pool_.notify();
  });
  pool_.start();
}

void JobRunner::stop() {
  rescuing_.reset();
  pool_.stop();
}

}  // namespace stoss::server::jobs
