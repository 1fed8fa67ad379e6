#pragma once
/// @file `stoss run` on several MPI ranks (docs/many_machines.md, "One run on several MPI ranks"): `--ranks
/// N` starts mpiexec, and each rank of a launch prepares its run. Every rank holds the whole model and
/// computes every step alike but for the elements, which the ranks share (core/parallel/element_share.hpp);
/// PETSc's GMRES + GAMG solves each Newton system over the ranks, each rank passing its own rows
/// (core/solve/petsc/petsc_amg_solver.cpp), and hands every rank the whole solution. Rank 0 writes the
/// result; the others write into a private directory, removed at the end.

#include <optional>
#include <string>
#include <vector>

namespace stoss::cli {

/// Why `--ranks N` (or the scene's solver.ranks: `asked_by`) cannot run here, or nothing: N must be at least
/// 1 and at most the cores (hardware threads) of this machine, the slots mpiexec_command gives.
std::optional<std::string> ranks_problem(int ranks, int cores, const std::string& asked_by = "--ranks");

/// The command line that starts `stoss run ARGS` on N ranks: mpiexec -n N (with --allow-run-as-root as root,
/// the hardware threads as slots, no binding) and this executable, ARGS without `--ranks N`.
std::vector<std::string> mpiexec_command(const std::vector<std::string>& run_args, int ranks, bool as_root,
                                         const std::string& executable);

/// Replaces this process by mpiexec_command; returns only when it cannot, with the reason.
std::string launch_ranks(const std::vector<std::string>& run_args, int ranks);

}  // namespace stoss::cli
