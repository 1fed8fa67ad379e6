#pragma once
/// @file What a run on several MPI ranks changes in its model (docs/many_machines.md, "One run on several MPI
/// ranks"): every rank holds the whole model and computes every step alike but for the elements, which the
/// ranks share (core/parallel/element_share.hpp), and the linear solves, which PETSc spreads over them.
/// `stoss run` (server/cli/ranks.hpp) and a job's process (server/jobs/running/job_process.hpp) both call it.

#include <filesystem>
#include <string>

#include "core/model/model.hpp"
#include "core/parallel/mpi_place.hpp"

namespace stoss::run {

/// On several ranks: solver.linear "auto" becomes "petsc_gamg" ("direct" solves with MUMPS,
/// core/run/solver_choice.cpp), and each rank runs cores / ranks element threads unless STOSS_THREADS says
/// otherwise. Then waits for every rank (core/solve/petsc_solver.hpp, synchronize_ranks), partitions the
/// nodes with them (partition_nodes) and shares the element loop by that partition. Nothing on a process of
/// its own.
/// @throws std::invalid_argument when the scene asks for a solver that runs on one rank; std::runtime_error
/// when MPI does not see the place the launcher's environment gave (srun without a PMI plugin).
void prepare_for_ranks(model::Model& m, parallel::MpiPlace place);

/// What one rank of a launch changes in its run; nothing for a process of its own. Rank 0 writes the run's
/// files; rank k > 0 keeps its checkpoints, and no result, in a private directory ($TMPDIR/stoss-rank-k-PID),
/// removed at its end (and by the next rank to start, when its rank was killed), and prints nothing on
/// stdout. Its checkpoints keep its Newton iterations those of rank 0: a step that may checkpoint refreshes
/// the factorisation only where a checkpoint store exists (core/run/simulate.cpp, keep_checkpoint).
class RankRun {
 public:
  /// `out_dir`: the run's directory; on rank k > 0 it becomes the private one, with a copy of the checkpoint
  /// of `out_dir` when resuming (so call it once rank 0 has settled which checkpoint it resumes from).
  RankRun(parallel::MpiPlace place, std::string& out_dir, bool resume);
  ~RankRun();
  RankRun(const RankRun&) = delete;
  RankRun& operator=(const RankRun&) = delete;
  /// Rank 0, or a process of its own: prints and writes the run's result.
  bool reports() const { return place_.rank == 0; }
  /// prepare_for_ranks.
  void prepare(model::Model& m) const { prepare_for_ranks(m, place_); }

 private:
  parallel::MpiPlace place_;
  std::filesystem::path private_dir_;
};

}  // namespace stoss::run
