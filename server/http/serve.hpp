#pragma once
/// @file The HTTP side of `stoss serve` (the subcommand is server/cli/serve.hpp): binds the API of a job
/// runner to an address and serves it until a stop signal.

#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

#include "server/common/stop_signals.hpp"
#include "server/http/limits.hpp"
#include "server/jobs/clock.hpp"
#include "server/jobs/running/job_runner.hpp"

namespace stoss::server::http {

/// The flags of `stoss serve` that concern HTTP, with their defaults.
struct HttpOptions {
  std::string host = "127.0.0.1";                   ///< --listen HOST:PORT
  int port = 8080;                                  ///< 0: any free port (printed at start)
  std::optional<std::filesystem::path> token_file;  ///< --token-file F
  /// --max-body-bytes, --max-nodes, --max-steps, --max-frames, --max-queue, --request-timeout,
  /// --max-mesh-store-bytes
  Limits limits;
  /// --http-threads: connections served at once, one thread each (a stalled upload holds one for at most
  /// the read timeout per read; further connections wait in the accept queue).
  int http_threads = 128;
  /// --max-connections-per-client: connections one client address may hold at once; more get 503 and are
  /// closed (connection_limit.hpp). Half the default threads: one client cannot take them all.
  int max_connections_per_client = 64;
  jobs::Millis read_timeout = 5'000;  ///< --read-timeout: longest wait for the next bytes of a request
};

/// The listening port is taken (by another server or anything else): exit 2, not a second listener.
class AddressInUse : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Serves the API (routes.hpp behind request_gate.hpp) of `runner`'s store and pool on options.host:port
/// until `signals` sees SIGINT or SIGTERM. `listening(port)` is called once the port is bound, before the
/// first request is answered. Throws AddressInUse, or std::runtime_error when it cannot listen or read the
/// token file.
void serve_http(const HttpOptions& options, jobs::JobRunner& runner, StopSignals& signals,
                const std::function<void(int port)>& listening);

}  // namespace stoss::server::http
