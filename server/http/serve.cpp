#include "server/http/serve.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <pthread.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <iostream>
#include <map>
#include <mutex>
#include <thread>

#include "server/common/stop_signals.hpp"
#include "server/http/connection_limit.hpp"
#include "server/http/options.hpp"
#include "server/http/request_gate.hpp"
#include "server/jobs/job_runner.hpp"

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
      const StopSignalRoute route;  // signals a library's own threads receive come here
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

/// The listening port is taken (by another server or anything else): exit 2, not a second listener.
class AddressInUse : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// cpp-httplib listens with a backlog of 5 (CPPHTTPLIB_LISTEN_BACKLOG, compiled into the library): 50
/// clients connecting at once overflow it, and the kernel's SYN retries then cost them 1 s, 3 s, ... before
/// the first byte. listen() again on the bound socket raises the backlog.
class Server : public httplib::Server {
 public:
  bool raise_backlog(int backlog) { return ::listen(svr_sock_, backlog) == 0; }
};

/// Binds `server` to host:port with SO_REUSEADDR only (no SO_REUSEPORT: a second server on the same port
/// must fail, not share the connections). Returns the port; throws AddressInUse or runtime_error.
int bind_server(httplib::Server& server, const std::string& host, int port) {
  server.set_socket_options([](socket_t sock) {
    const int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  errno = 0;
  const int bound = port == 0 ? server.bind_to_any_port(host) : (server.bind_to_port(host, port) ? port : -1);
  const int error = errno;
  if (bound > 0) return bound;
  if (error == EADDRINUSE)
    throw AddressInUse("cannot listen on " + host + ":" + std::to_string(port) +
                       ": address in use (is another stoss serve running on this port?)");
  throw std::runtime_error("cannot listen on " + host + ":" + std::to_string(port) +
                           (error ? std::string(": ") + std::strerror(error) : std::string()));
}

int run(const ServeOptions& options) {
  SignalWaiter signals;
  jobs::SystemClock clock;
  const jobs::StoreLocation location = store_location(options);
  jobs::JobRunner runner(job_runner_options(options, location), clock);
  std::optional<BearerAuth> auth;
  if (options.token_file) auth = BearerAuth::from_file(*options.token_file);
  App app{runner.store(), runner.pool(), runner.files(), options.limits, auth, {}};

  Server server;
  server.set_payload_max_length(options.limits.max_body_bytes);
  // The head and the body of a response go out in two writes; with Nagle a kept-alive client waits for
  // the ACK of the first (~40 ms) before the second. TCP_NODELAY is set on the listening socket, and
  // Linux hands it down to every accepted socket.
  server.set_tcp_nodelay(true);
  const auto threads = static_cast<std::size_t>(options.http_threads);
  ConnectionLimit connection_limit(options.max_connections_per_client);
  server.new_task_queue = [threads, &connection_limit] { return counting_thread_pool(threads, connection_limit); };
  const auto timeout = std::chrono::milliseconds(options.read_timeout);
  server.set_read_timeout(timeout);
  server.set_write_timeout(std::max(timeout, std::chrono::milliseconds(5000)));
  server.set_keep_alive_max_count(10'000);
  server.set_keep_alive_timeout(std::max<time_t>(1, static_cast<time_t>(options.read_timeout / 1000)));
  install_request_defaults(server, app, &connection_limit);
  install_error_handling(server, app.metrics, options.limits);
  install_routes(server, app);
  const int port = bind_server(server, options.host, options.port);
  if (!server.raise_backlog(1024)) std::cerr << "stoss serve: cannot raise the listen backlog" << std::endl;

  signals.start(server);
  runner.start();
  std::cout << "stoss serve: listening on http://" << options.host << ":" << port << " (data "
            << options.data.string() << (options.store ? ", store " + location.describe() : std::string())
            << ", " << options.pool.workers << " workers)" << std::endl;
  server.listen_after_bind();
  signals.stop();
  runner.stop();
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
  } catch (const jobs::StoreOpenError& e) {
    std::cerr << "stoss serve: " << e.what() << std::endl;
    return 2;
  } catch (const AddressInUse& e) {
    std::cerr << "stoss serve: " << e.what() << std::endl;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "stoss serve: " << e.what() << std::endl;
    return 1;
  }
}

}  // namespace stoss::server
