#include "server/cli/worker.hpp"

#include <iostream>

#include "server/common/stop_signals.hpp"

namespace stoss::cli {

namespace {

namespace jobs = server::jobs;

int run(const WorkerOptions& options) {
  server::StopSignals signals;  // before any thread
  jobs::SystemClock clock;
  const jobs::StoreLocation location = store_location(options);
  jobs::JobRunner runner(job_runner_options(options, location), clock);
  runner.start();
  std::cout << "stoss worker: " << runner.pool().name() << " running " << options.pool.workers
            << " workers (store " << location.describe() << ", data " << options.data.string() << ")"
            << std::endl;
  const int received = signals.wait();
  std::cout << "stoss worker: " << server::stop_signal_name(received) << ", stopping" << std::endl;
  runner.stop();
  std::cout << "stoss worker: stopped" << std::endl;
  return 0;
}

}  // namespace

WorkerOptions parse_worker_options(const std::vector<std::string>& args) {
  static const FlagTable<WorkerOptions> table = with_runner_flags(FlagTable<WorkerOptions>{});
  WorkerOptions options;
  parse_flags(args, table, options);
  check_runner_flags(options);
  if (options.pool.workers == 0) throw UsageError("--workers needs an integer in [1, 256], got '0'");
  return options;
}

std::string worker_usage() {
  return std::string(R"(usage: stoss worker --store STORE [options]

Runs queued jobs without HTTP until SIGINT or SIGTERM (then gives running jobs back to the queue).
API processes (`stoss serve`, possibly with --workers 0) queue the jobs; every process shares the store
and the data directory.

  --store STORE          postgresql://USER[:PASSWORD]@HOST:PORT/DB (libpq's PG* variables and PGPASSFILE
                         fill what the URL leaves out) or sqlite:PATH (default sqlite:DIR/jobs.db)
  --data DIR             results and logs (DIR/jobs/<id>/), shared with the API processes (default ./var)
  --workers N            jobs run at once in this process (default 2)
  --job-timeout S        wall-time limit of one job attempt; 0: none (default 0)
)") + runner_flags_usage();
}

int worker_command(const std::vector<std::string>& args) {
  return run_subcommand("worker", args, worker_usage(), [&] { return run(parse_worker_options(args)); });
}

}  // namespace stoss::cli
