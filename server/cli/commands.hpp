#pragma once
/// @file The command-line subcommands that run the core without a server.

#include <string>
#include <vector>

namespace stoss::cli {

/// Exit codes of `stoss run` and `stoss validate`.
enum ExitCode { success = 0, solver_failure = 1, invalid_scene = 2, suspect_result = 3 };

/// `stoss run SCENE.json -o DIR`: writes DIR/result.h5 and DIR/result.xdmf, progress on stderr.
int run_command(const std::vector<std::string>& args);
/// `stoss study SCENE.json --steps h1,h2,… [--schemes a,b] [--reference H] [--csv | --json]`: the
/// accuracy-against-time table of the scene (core/study).
int study_command(const std::vector<std::string>& args);
/// `stoss validate SCENE.json [--json]`: effects, node and DOF counts, steps, or every error.
int validate_command(const std::vector<std::string>& args);

}  // namespace stoss::cli
