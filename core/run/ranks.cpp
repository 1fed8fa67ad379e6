#include "core/run/ranks.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/output/result_writer.hpp"
#include "core/parallel/element_share.hpp"
#include "core/parallel/worker_threads.hpp"
#include "core/solve/petsc_solver.hpp"

namespace stoss::run {

void prepare_for_ranks(model::Model& m, parallel::MpiPlace place) {
  if (!place.several()) return;
  if (m.solver.linear == model::LinearSolver::automatic) m.solver.linear = model::LinearSolver::petsc_gamg;
  if (m.solver.linear == model::LinearSolver::iterative)
    throw std::invalid_argument("/solver/linear: \"iterative\" solves on one rank; on " +
                                std::to_string(place.size) +
                                " MPI ranks it must be \"petsc_gamg\", \"direct\" (MUMPS) or \"auto\"");
  if (!std::getenv("STOSS_THREADS")) {
    parallel::set_worker_threads(std::max(1, parallel::machine_cores() / place.size));
  }
  solve::synchronize_ranks();
  if (const auto [rank, size] = solve::world_place(); rank != place.rank || size != place.size)
    throw std::runtime_error("the launcher started " + std::to_string(place.size) +
                             " processes, but MPI joined " + std::to_string(size) +
                             " of them into one launch: with srun, pass --mpi=pmix (docs/many_machines.md)");
  std::vector<int> offsets, neighbours;
  parallel::node_graph(m.mesh.hex8, m.mesh.node_count(), offsets, neighbours);
  std::vector<int> node_part = solve::partition_nodes(offsets, neighbours);
  parallel::set_element_share(
      parallel::share_of(m.mesh.hex8, std::move(node_part), place.rank, place.size, solve::sum_over_ranks));
}

namespace fs = std::filesystem;

namespace {

constexpr const char* private_dir_prefix = "stoss-rank-";

/// True when process `pid` has ended: no such process, or one that died and waits to be reaped (a zombie,
/// whose orphaned rank no init process reaps in a container).
bool process_ended(long pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
  const auto name_end = line.rfind(')');  // the state follows the command's name in parentheses
  return name_end != std::string::npos && name_end + 2 < line.size() && line[name_end + 2] == 'Z';
}

/// Removes the private folders in `temp` of ranks that died without removing theirs (killed with their
/// launcher): stoss-rank-<k>-<pid> whose process has ended.
void remove_orphaned_private_dirs(const fs::path& temp) {
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(temp, error)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(private_dir_prefix, 0) != 0) continue;
    const auto dash = name.rfind('-');
    const long pid = std::strtol(name.c_str() + dash + 1, nullptr, 10);
    if (pid > 0 && process_ended(pid)) fs::remove_all(entry, error);
  }
}

}  // namespace

RankRun::RankRun(parallel::MpiPlace place, std::string& out_dir, bool resume) : place_(place) {
  if (place_.rank == 0) return;
  const fs::path temp = fs::temp_directory_path();
  remove_orphaned_private_dirs(temp);
  private_dir_ = temp / (private_dir_prefix + std::to_string(place_.rank) + "-" + std::to_string(::getpid()));
  fs::remove_all(private_dir_);
  fs::create_directories(private_dir_);
  const fs::path checkpoint = fs::path(out_dir) / output::checkpoint_directory_name;
  if (resume && fs::exists(checkpoint))
    fs::copy(checkpoint, private_dir_ / output::checkpoint_directory_name, fs::copy_options::recursive);
  out_dir = private_dir_.string();
  if (!std::freopen("/dev/null", "w", stdout)) std::perror("stoss: rank stdout");
}

RankRun::~RankRun() {
  std::error_code error;
  if (!private_dir_.empty()) fs::remove_all(private_dir_, error);
}

}  // namespace stoss::run
