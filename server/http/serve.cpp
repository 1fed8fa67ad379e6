#include "server/http/serve.hpp"

#include <pthread.h>
#include <signal.h>

#include <iostream>
#include <thread>

#include "server/http/options.hpp"
#include "server/http/routes.hpp"
#include "server/jobs/inprocess_executor.hpp"
#include "server/jobs/periodic.hpp"
#include "server/jobs/rescuer.hpp"
#include "server/jobs/sqlite_store.hpp"

namespace stoss::server {

namespace {

using namespace stoss::server::http;

/// Blocks SIGINT and SIGTERM in this thread and every thread started after (so construct it before any
/// thread); once started, a dedicated thread waits for them with sigwait and stops the server.
class SignalWaiter {
 public:
  SignalWaiter() {
    sigemptyset(&signals_);
    sigaddset(&signals_, SIGINT);
    sigaddset(&signals_, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &signals_, &previous_);
    signal(SIGPIPE, SIG_IGN);
  }
  void start(httplib::Server& server) {
    thread_ = std::thread([this, &server] {
      int received = 0;
      sigwait(&signals_, &received);
      if (done_) return;
      std::cout << "stoss serve: " << (received == SIGINT ? "SIGINT" : "SIGTERM") << ", stopping"
                << std::endl;
      while (!server.is_running() && !done_) std::this_thread::sleep_for(std::chrono::milliseconds(10));
      server.stop();
    });
  }
  /// Ends the waiting thread (call before the server it stops goes away).
  void stop() {
    done_ = true;
    if (!thread_.joinable()) return;
    pthread_kill(thread_.native_handle(), SIGTERM);  // blocked and awaited: wakes sigwait, kills nothing
    thread_.join();
  }
  ~SignalWaiter() {
    stop();
    pthread_sigmask(SIG_SETMASK, &previous_, nullptr);
  }

 private:
  sigset_t signals_{}, previous_{};
  std::atomic<bool> done_{false};
  std::thread thread_;
};

int run(const ServeOptions& options) {
  SignalWaiter signals;
  std::filesystem::create_directories(options.data / "jobs");
  jobs::SystemClock clock;
  jobs::SqliteStore store(options.data / "jobs.db", clock);
  jobs::JobFiles files(options.data);
  jobs::InProcessExecutor executor(files, clock);
  jobs::WorkerPool pool(store, executor, options.pool);
  std::optional<BearerAuth> auth;
  if (options.token_file) auth = BearerAuth::from_file(*options.token_file);
  App app{store, pool, files, options.limits, auth, {}};

  httplib::Server server;
  server.set_payload_max_length(options.limits.max_body_bytes);
  install_request_defaults(server);
  install_error_handling(server, app.metrics);
  install_routes(server, app);
  const int port = options.port == 0 ? server.bind_to_any_port(options.host)
                                     : (server.bind_to_port(options.host, options.port) ? options.port : -1);
  if (port < 0)
    throw std::runtime_error("cannot listen on " + options.host + ":" + std::to_string(options.port));

  jobs::Rescuer rescuer(store, clock, options.max_attempts);
  rescuer.run_once();  // jobs of a dead process whose lease already ran out go back to the queue first
  jobs::Periodic rescuing("rescuer", std::chrono::milliseconds(options.pool.renew_every), [&] {
    if (rescuer.run_once().requeued > 0) pool.notify();
  });
  signals.start(server);
  pool.start();
  std::cout << "stoss serve: listening on http://" << options.host << ":" << port << " (data "
            << options.data.string() << ", " << options.pool.workers << " workers)" << std::endl;
  server.listen_after_bind();
  signals.stop();
  pool.stop();
  std::cout << "stoss serve: stopped" << std::endl;
  return 0;
}

}  // namespace

int serve_command(const std::vector<std::string>& args) {
  if (!args.empty() && (args[0] == "--help" || args[0] == "-h")) {
    std::cout << serve_usage();
    return 0;
  }
  try {
    return run(parse_serve_options(args));
  } catch (const UsageError& e) {
    std::cerr << "stoss serve: " << e.what() << "\n\n" << serve_usage();
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "stoss serve: " << e.what() << std::endl;
    return 1;
  }
}

}  // namespace stoss::server
