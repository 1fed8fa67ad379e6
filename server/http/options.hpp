#pragma once
/// @file ServeOptions: the flags of `stoss serve`, with their defaults.

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "server/http/limits.hpp"
#include "server/jobs/job_runner.hpp"
#include "server/jobs/open_store.hpp"
#include "server/jobs/worker_pool.hpp"

namespace stoss::server::http {

struct ServeOptions {
  std::string host = "127.0.0.1";                   ///< --listen HOST:PORT
  int port = 8080;                                  ///< 0: any free port (printed at start)
  std::filesystem::path data = "var";               ///< --data DIR: jobs.db and jobs/<id>/
  std::optional<jobs::StoreLocation> store;         ///< --store; unset: sqlite:DATA/jobs.db
  std::optional<std::filesystem::path> token_file;  ///< --token-file F
  jobs::WorkerPoolOptions pool;                     ///< --workers, --lease-seconds, --renew-seconds
  int max_attempts = 3;  ///< --max-attempts: runs before an expired lease fails a job
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
  jobs::Millis job_timeout = 0;       ///< --job-timeout: wall-time limit of one job attempt (0: none)
  std::size_t job_memory = 0;         ///< --job-memory: address-space limit of a job's process (0: none)
};

/// A command line `stoss serve` cannot work with; the message says which flag and why.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Parses the arguments after `stoss serve`. Throws UsageError.
ServeOptions parse_serve_options(const std::vector<std::string>& args);

/// The usage text of `stoss serve` with every flag and its default.
std::string serve_usage();

/// Parses the arguments after `stoss worker`: the flags of `serve` that concern running jobs (--store,
/// --data, --workers, --lease-seconds, --renew-seconds, --max-attempts, --job-timeout, --job-memory).
/// Throws UsageError, also for a flag only `serve` has.
ServeOptions parse_worker_options(const std::vector<std::string>& args);

/// The usage text of `stoss worker`.
std::string worker_usage();

/// The store the options name: --store, or sqlite:DATA/jobs.db.
jobs::StoreLocation store_location(const ServeOptions& options);

/// What a process's job runner needs of the options (`stoss serve` and `stoss worker`).
jobs::JobRunnerOptions job_runner_options(const ServeOptions& options, const jobs::StoreLocation& location);

}  // namespace stoss::server::http
