#include "server/cli/worker.hpp"

#include <pthread.h>
#include <signal.h>

#include <iostream>

#include "server/common/stop_signals.hpp"
#include "server/http/options.hpp"
#include "server/jobs/job_runner.hpp"

namespace stoss::cli {

namespace {

using namespace stoss::server;

/// SIGINT and SIGTERM, blocked in this thread and every thread started after; wait() returns the one
/// that came.
class Signals {
 public:
  Signals() {
    sigemptyset(&set_);
    sigaddset(&set_, SIGINT);
    sigaddset(&set_, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &set_, nullptr);
    signal(SIGPIPE, SIG_IGN);
  }
  int wait() {
    const StopSignalRoute route;  // signals a library's own threads receive come here
    int received = 0;
    sigwait(&set_, &received);
    return received;
  }

 private:
  sigset_t set_{};
};

int run(const http::ServeOptions& options) {
  Signals signals;
  jobs::SystemClock clock;
  const jobs::StoreLocation location = http::store_location(options);
  jobs::JobRunner runner(http::job_runner_options(options, location), clock);
  runner.start();
  std::cout << "stoss worker: " << runner.pool().name() << " running " << options.pool.workers
            << " workers (store " << location.describe() << ", data " << options.data.string() << ")"
            << std::endl;
  const int received = signals.wait();
  std::cout << "stoss worker: " << (received == SIGINT ? "SIGINT" : "SIGTERM") << ", stopping" << std::endl;
  runner.stop();
  std::cout << "stoss worker: stopped" << std::endl;
  return 0;
}

}  // namespace

int worker_command(const std::vector<std::string>& args) {
  if (!args.empty() && (args[0] == "--help" || args[0] == "-h")) {
    std::cout << http::worker_usage();
    return 0;
  }
  try {
    return run(http::parse_worker_options(args));
  } catch (const http::UsageError& e) {
    std::cerr << "stoss worker: " << e.what() << "\n\n" << http::worker_usage();
    return 2;
  } catch (const jobs::StoreOpenError& e) {
    std::cerr << "stoss worker: " << e.what() << std::endl;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "stoss worker: " << e.what() << std::endl;
    return 1;
  }
}

}  // namespace stoss::cli
