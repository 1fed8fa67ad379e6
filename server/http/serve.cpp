#include "server/http/serve.hpp"

#include <netinet/in.h>
#include <sys/socket.h>

#include <cerrno>
#include <cstring>
#include <iostream>
#include <thread>

#include "server/http/connection_limit.hpp"
#include "server/http/request_gate.hpp"
#include "server/http/routes.hpp"

namespace stoss::server::http {

namespace {

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

/// Timeouts and keep-alive: a read waits at most --read-timeout, a write at least 5 s.
void set_timeouts(httplib::Server& server, jobs::Millis read_timeout) {
  const auto timeout = std::chrono::milliseconds(read_timeout);
  server.set_read_timeout(timeout);
  server.set_write_timeout(std::max(timeout, std::chrono::milliseconds(5000)));
  server.set_keep_alive_max_count(10'000);
  server.set_keep_alive_timeout(std::max<time_t>(1, static_cast<time_t>(read_timeout / 1000)));
}

}  // namespace

void serve_http(const HttpOptions& options, jobs::JobRunner& runner, StopSignals& signals,
                const std::function<void(int port)>& listening) {
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
  server.new_task_queue = [threads, &connection_limit] {
    return counting_thread_pool(threads, connection_limit);
  };
  set_timeouts(server, options.read_timeout);
  install_request_defaults(server, app, &connection_limit);
  install_error_handling(server, app.metrics, options.limits);
  install_routes(server, app);
  const int port = bind_server(server, options.host, options.port);
  if (!server.raise_backlog(1024)) std::cerr << "stoss serve: cannot raise the listen backlog" << std::endl;

  struct StopWaitingAtExit {  // also when listening() throws: the waiting thread touches `server`
    StopSignals& signals;
    ~StopWaitingAtExit() { signals.stop_waiting(); }
  } stop_waiting_at_exit{signals};
  signals.on_stop([&server, &signals](int received) {
    std::cout << "stoss serve: " << stop_signal_name(received) << ", stopping" << std::endl;
    while (!server.is_running() && !signals.stopping())
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    server.stop();
  });
  listening(port);
  server.listen_after_bind();
}

}  // namespace stoss::server::http
