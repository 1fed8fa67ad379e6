#include "server/cli/ranks.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/output/result_writer.hpp"
#include "core/parallel/element_share.hpp"
#include "core/parallel/worker_threads.hpp"
#include "core/solve/petsc_solver.hpp"

namespace stoss::cli {

namespace fs = std::filesystem;

std::optional<std::string> ranks_problem(int ranks, int cores) {
  if (ranks < 1) return "--ranks must be at least 1, got " + std::to_string(ranks);
  if (ranks > cores)
    return "--ranks must be at most the " + std::to_string(cores) + " cores of this machine, got " +
           std::to_string(ranks) +
           " (on a cluster, start the ranks with its launcher: docs/many_machines.md)";
  return std::nullopt;
}

std::vector<std::string> mpiexec_command(const std::vector<std::string>& run_args, int ranks, bool as_root,
                                         const std::string& executable) {
  std::vector<std::string> command{"mpiexec", "-n", std::to_string(ranks)};
  if (as_root) command.push_back("--allow-run-as-root");  // Open MPI refuses root without it
  // Slots are the hardware threads (what ranks_problem counts), and no binding: each rank runs its share of
  // the element threads.
  command.insert(command.end(), {"--use-hwthread-cpus", "--bind-to", "none", executable, "run"});
  for (size_t i = 0; i < run_args.size(); ++i) {
    if (run_args[i] == "--ranks") {
      ++i;  // and its value
      continue;
    }
    command.push_back(run_args[i]);
  }
  return command;
}

std::string launch_ranks(const std::vector<std::string>& run_args, int ranks) {
  std::error_code error;
  const fs::path executable = fs::read_symlink("/proc/self/exe", error);
  if (error) return "cannot find this executable (/proc/self/exe): " + error.message();
  const auto command = mpiexec_command(run_args, ranks, geteuid() == 0, executable.string());
  std::vector<char*> argv;
  for (const std::string& word : command) argv.push_back(const_cast<char*>(word.c_str()));
  argv.push_back(nullptr);
  std::fflush(stdout);
  execvp(argv[0], argv.data());
  return std::string("cannot start mpiexec: ") + std::strerror(errno) +
         " (install openmpi-bin, deploy/packages.txt)";
}

RankRun::RankRun(parallel::MpiPlace place, std::string& out_dir, bool resume) : place_(place) {
  if (place_.rank == 0) return;
  private_dir_ = fs::temp_directory_path() /
                 ("stoss-rank-" + std::to_string(place_.rank) + "-" + std::to_string(::getpid()));
  fs::remove_all(private_dir_);
  fs::create_directories(private_dir_);
  const fs::path checkpoint = fs::path(out_dir) / output::checkpoint_directory_name;
  if (resume && fs::exists(checkpoint))
    fs::copy(checkpoint, private_dir_ / output::checkpoint_directory_name, fs::copy_options::recursive);
  out_dir = private_dir_.string();
  if (!std::freopen("/dev/null", "w", stdout)) std::perror("stoss run: rank stdout");
}

RankRun::~RankRun() {
  std::error_code error;
  if (!private_dir_.empty()) fs::remove_all(private_dir_, error);
}

void RankRun::prepare(model::Model& m) const {
  if (!place_.several()) return;
  if (m.solver.linear == model::LinearSolver::automatic) m.solver.linear = model::LinearSolver::petsc_gamg;
  if (m.solver.linear == model::LinearSolver::iterative)
    throw std::invalid_argument("/solver/linear: \"iterative\" solves on one rank; on " +
                                std::to_string(place_.size) +
                                " MPI ranks it must be \"petsc_gamg\", \"direct\" (MUMPS) or \"auto\"");
  if (!std::getenv("STOSS_THREADS")) {
    parallel::set_worker_threads(std::max(1, parallel::machine_cores() / place_.size));
  }
  solve::synchronize_ranks();
  parallel::set_element_share({place_.rank, place_.size, solve::sum_over_ranks});
}

}  // namespace stoss::cli
