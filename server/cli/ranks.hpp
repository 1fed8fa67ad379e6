#pragma once
/// @file `stoss run` on several MPI ranks (docs/many_machines.md, "One run on several MPI ranks"): `--ranks
/// N` starts mpiexec, and each rank of a launch prepares its run. Every rank holds the whole model and
/// computes every step alike but for the elements, which the ranks share (core/parallel/element_share.hpp);
/// PETSc's GMRES + GAMG solves each Newton system over the ranks, each rank passing its own rows
/// (core/solve/petsc/petsc_amg_solver.cpp), and hands every rank the whole solution. Rank 0 writes the
/// result; the others write into a private directory, removed at the end.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/model/model.hpp"
#include "core/parallel/mpi_place.hpp"

namespace stoss::cli {

/// Why `--ranks N` cannot run here, or nothing: N must be at least 1 and at most the cores (hardware threads)
/// of this machine, the slots mpiexec_command gives.
std::optional<std::string> ranks_problem(int ranks, int cores);

/// The command line that starts `stoss run ARGS` on N ranks: mpiexec -n N (with --allow-run-as-root as root,
/// the hardware threads as slots, no binding) and this executable, ARGS without `--ranks N`.
std::vector<std::string> mpiexec_command(const std::vector<std::string>& run_args, int ranks, bool as_root,
                                         const std::string& executable);

/// Replaces this process by mpiexec_command; returns only when it cannot, with the reason.
std::string launch_ranks(const std::vector<std::string>& run_args, int ranks);

/// What one rank of a launch changes in its run; nothing for a process of its own.
class RankRun {
 public:
  /// `out_dir`: the run's directory; on rank k > 0 it becomes a private one (with a copy of the checkpoint
  /// of `out_dir` when resuming) and stdout is silenced.
  RankRun(parallel::MpiPlace place, std::string& out_dir, bool resume);
  ~RankRun();
  RankRun(const RankRun&) = delete;
  RankRun& operator=(const RankRun&) = delete;
  /// Rank 0, or a process of its own: prints and writes the run's result.
  bool reports() const { return place_.rank == 0; }
  /// Sets the model for the launch: solver.linear "auto" becomes "petsc_gamg" ("direct" solves with MUMPS,
  /// core/run/solver_choice.cpp), and each rank runs cores / ranks element threads unless STOSS_THREADS says
  /// otherwise. Then waits for every rank (core/solve/petsc_solver.hpp, synchronize_ranks) and shares the
  /// element loop with them.
  /// @throws std::invalid_argument when the scene asks for a solver that runs on one rank.
  void prepare(model::Model& m) const;

 private:
  parallel::MpiPlace place_;
  std::filesystem::path private_dir_;
};

}  // namespace stoss::cli
