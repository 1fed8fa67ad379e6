#pragma once
/// @file `stoss serve`: the job service from the command line.

#include <string>
#include <vector>

namespace stoss::server {

/// Runs `stoss serve` with `args` (everything after "serve"; flags in server/http/options.hpp) until
/// SIGINT or SIGTERM. Returns the process exit code: 0 after a clean stop, 2 on a usage error,
/// 1 when the server cannot start (store, token file, address in use).
int serve_command(const std::vector<std::string>& args);

}  // namespace stoss::server
