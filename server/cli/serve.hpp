#pragma once
/// @file `stoss serve`: the job service from the command line (the HTTP side is server/http/serve.hpp).

#include <string>
#include <vector>

#include "server/cli/flags.hpp"
#include "server/http/serve.hpp"

namespace stoss::cli {

/// The flags of `stoss serve`: those that run jobs (RunnerFlags) and those of HTTP.
struct ServeOptions : RunnerFlags, server::http::HttpOptions {};

/// Parses the arguments after `stoss serve`. Throws UsageError.
ServeOptions parse_serve_options(const std::vector<std::string>& args);

/// The usage text of `stoss serve` with every flag and its default.
std::string serve_usage();

/// Runs `stoss serve` with `args` (everything after "serve") until SIGINT or SIGTERM. Returns the process
/// exit code: 0 after a clean stop, 2 on a usage error, a store that cannot be opened or an address in
/// use, 1 when the server cannot start otherwise (token file).
int serve_command(const std::vector<std::string>& args);

}  // namespace stoss::cli
