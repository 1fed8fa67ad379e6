#include "server/jobs/job_runner.hpp"

namespace stoss::server::jobs {

namespace {

JobFiles prepared_files(const std::filesystem::path& data) {
  std::filesystem::create_directories(data / "jobs");
  return JobFiles(data);
}

}  // namespace

JobRunner::JobRunner(const JobRunnerOptions& options, const Clock& clock)
    : store_(open_store(options.store, clock)),
      files_(prepared_files(options.data)),
      // Each job runs in a process of its own (this binary, `stoss run-job`): a job that crashes or runs
      // over a limit fails alone.
      executor_(files_, options.data, std::filesystem::read_symlink("/proc/self/exe"), options.limits),
      pool_(*store_, executor_, pool_options_for(options.store, options.pool)),
      subscription_(store_->subscribe(
          {[this] { pool_.notify(); }, [this](const JobId& id) { pool_.cancel(id); }})),
      rescuer_(*store_, clock, options.max_attempts),
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
