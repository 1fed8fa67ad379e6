#include "server/cli/ranks.hpp"

#include <unistd.h>

#include "server/jobs/running/launcher.hpp"

namespace stoss::cli {

std::optional<std::string> ranks_problem(int ranks, int cores, const std::string& asked_by) {
  if (ranks < 1) return asked_by + " must be at least 1, got " + std::to_string(ranks);
  if (ranks > cores)
    return asked_by + " must be at most the " + std::to_string(cores) + " cores of this machine, got " +
           std::to_string(ranks) +
           " (on a cluster, start the ranks with its launcher: docs/many_machines.md)";
  return std::nullopt;
}

std::vector<std::string> mpiexec_command(const std::vector<std::string>& run_args, int ranks, bool as_root,
                                         const std::string& executable) {
  std::vector<std::string> command{executable, "run"};
  for (size_t i = 0; i < run_args.size(); ++i) {
    if (run_args[i] == "--ranks") {
      ++i;  // and its value
      continue;
    }
    command.push_back(run_args[i]);
  }
  return server::jobs::launcher_command(server::jobs::default_launcher(as_root), ranks, command);
}

std::string launch_ranks(const std::vector<std::string>& run_args, int ranks) {
  try {
    const auto command = mpiexec_command(run_args, ranks, geteuid() == 0, server::jobs::this_executable());
    return server::jobs::exec_command(command) + " (install openmpi-bin, deploy/packages.txt)";
  } catch (const std::exception& e) {
    return e.what();
  }
}

}  // namespace stoss::cli
