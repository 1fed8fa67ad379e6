#include "server/cli/worker.hpp"

#include <pthread.h>
#include <signal.h>

#include <iostream>

#include "server/http/options.hpp"
#include "server/jobs/open_store.hpp"
#include "server/jobs/periodic.hpp"
#include "server/jobs/process_executor.hpp"
#include "server/jobs/rescuer.hpp"

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
  const std::unique_ptr<jobs::JobStore> store = jobs::open_store(location, clock);
  std::filesystem::create_directories(options.data / "jobs");
  jobs::JobFiles files(options.data);
  jobs::ProcessExecutor executor(files, options.data, std::filesystem::read_symlink("/proc/self/exe"),
                                 {options.job_timeout, options.job_memory});
  jobs::WorkerPool pool(*store, executor, jobs::pool_options_for(location, options.pool));
  const auto subscription =
      store->subscribe({[&pool] { pool.notify(); }, [&pool](const jobs::JobId& id) { pool.cancel(id); }});
  jobs::Rescuer rescuer(*store, clock, options.max_attempts);
  jobs::Periodic rescuing("rescuer", std::chrono::milliseconds(options.pool.renew_every), [&] {
    if (rescuer.run_once().requeued > 0) pool.notify();
  });
  pool.start();
  std::cout << "stoss worker: " << pool.name() << " running " << options.pool.workers << " workers (store "
            << location.describe() << ", data " << options.data.string() << ")" << std::endl;
  const int received = signals.wait();
  std::cout << "stoss worker: " << (received == SIGINT ? "SIGINT" : "SIGTERM") << ", stopping" << std::endl;
  rescuing.stop();
  pool.stop();
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
