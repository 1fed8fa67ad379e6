// stoss: run | validate | study | serve | worker (and run-job, the process of one job of `serve`).
#include <malloc.h>

#include <iostream>
#include <string>
#include <vector>

#include "server/cli/commands.hpp"
#include "server/cli/run_job.hpp"
#include "server/cli/serve.hpp"
#include "server/cli/worker.hpp"

namespace {
constexpr const char* usage_text =
    "usage: stoss <command> [args]\n"
    "  run SCENE.json [-o DIR]     simulate; writes DIR/result.h5 and DIR/result.xdmf (exit 0 ok, 1 solver, "
    "2 scene)\n"
    "  run --resume DIR            go on from DIR's checkpoint after a crash; writes the same result\n"
    "  validate SCENE.json [--json] check a scene: effects, node/DOF counts, steps, or every error\n"
    "  study SCENE.json --steps h1,h2,... [--schemes a,b] [--reference H] [--csv|--json]\n"
    "                              error and wall time per scheme and step size against a fine reference\n"
    "  serve [--listen HOST:PORT] [--data DIR] [--store STORE] [--workers N] [--token-file F]\n"
    "                              the job service\n"
    "  worker --store STORE --data DIR [--workers N]   run queued jobs of a shared store, without HTTP\n"
    "  --help, --version\n"
    "`stoss <command> --help` describes a command.\n";
}

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << usage_text;
    return 2;
  }
  const std::string command = argv[1];
  const std::vector<std::string> args(argv + 2, argv + argc);
  if (command == "run") return stoss::cli::run_command(args);
  if (command == "study") return stoss::cli::study_command(args);
  if (command == "validate") return stoss::cli::validate_command(args);
  if (command == "serve") {
    // Freed request memory (a parsed mesh, a validated scene) stays in glibc's per-thread arenas, one per
    // HTTP thread at most 8 × cores of them: two arenas give it back (docs/measurements.md, "Hardening
    // numbers").
    mallopt(M_ARENA_MAX, 2);
    return stoss::cli::serve_command(args);
  }
  if (command == "worker") return stoss::cli::worker_command(args);
  if (command == "run-job") return stoss::cli::run_job_command(args);
  if (command == "--help" || command == "-h" || command == "help") {
    std::cout << usage_text;
    return 0;
  }
  if (command == "--version") {
    std::cout << "stoss " << STOSS_VERSION << "\n";
    return 0;
  }
  std::cerr << "stoss: unknown command '" << command << "'\n" << usage_text;
  return 2;
}
