#pragma once
/// @file The launcher that starts a job's process on several MPI ranks (docs/many_machines.md, "Jobs on
/// several ranks"): a template of words, `{ranks}` standing for the job's ranks, after which the command of
/// one rank goes. `mpiexec -n {ranks} …` on one machine, `srun --mpi=pmix -n {ranks} …` where Slurm places
/// the ranks.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace stoss::server::jobs {

/// mpiexec -n {ranks} with the hardware threads as slots and no binding (each rank runs its share of the
/// element threads), and --allow-run-as-root when `as_root` (Open MPI refuses root without it).
std::string default_launcher(bool as_root);

/// Why `launcher` cannot start ranks, or nothing: it needs a program to run, and words split by spaces (no
/// quotes: a word with a space needs a wrapper script).
std::optional<std::string> launcher_problem(const std::string& launcher);

/// The launcher's words with `{ranks}` replaced by `ranks` and a last "…" or "..." (the place of the command,
/// as the docs write it) dropped, then `command`.
std::vector<std::string> launcher_command(const std::string& launcher, int ranks,
                                          const std::vector<std::string>& command);

/// This process's executable (/proc/self/exe), the command every rank runs. Throws std::runtime_error.
std::filesystem::path this_executable();

/// Replaces this process by `command` (its first word looked up in PATH); returns only when it cannot, with
/// the reason ("cannot start 'mpiexec': No such file or directory").
std::string exec_command(const std::vector<std::string>& command);

}  // namespace stoss::server::jobs
