#pragma once
/// @file `stoss worker`: runs queued jobs of a shared store without HTTP.

#include <string>
#include <vector>

#include "server/cli/flags.hpp"

namespace stoss::cli {

/// The flags of `stoss worker`: only those that run jobs.
struct WorkerOptions : RunnerFlags {};

/// Parses the arguments after `stoss worker` (--store, --data, --workers, --lease-seconds, --renew-seconds,
/// --max-attempts, --job-timeout, --job-memory). Throws UsageError, also for a flag only `serve` has and
/// for --workers 0.
WorkerOptions parse_worker_options(const std::vector<std::string>& args);

/// The usage text of `stoss worker`.
std::string worker_usage();

/// `stoss worker --store URL --data DIR --workers N`: claims and runs jobs until SIGINT or SIGTERM, then
/// gives the running ones back to the queue. Exit 0 on a signal, 2 on a bad command line or a store that
/// cannot be opened (unreachable, wrong credentials, malformed URL, newer schema).
int worker_command(const std::vector<std::string>& args);

}  // namespace stoss::cli
