#pragma once
/// @file `stoss worker`: runs queued jobs of a shared store without HTTP.

#include <string>
#include <vector>

namespace stoss::cli {

/// `stoss worker --store URL --data DIR --workers N`: claims and runs jobs until SIGINT or SIGTERM, then
/// gives the running ones back to the queue. Exit 0 on a signal, 2 on a bad command line or a store that
/// cannot be opened (unreachable, wrong credentials, malformed URL, newer schema).
int worker_command(const std::vector<std::string>& args);

}  // namespace stoss::cli
