#pragma once
/// @file The child side of ProcessExecutor: the process of one job attempt (`stoss run-job`, parsed in
/// server/cli/run_job.hpp). It dies with its parent, honours SIGTERM as a cancel within a step, runs the
/// attempt with an InProcessExecutor, relays progress on progress_fd and writes outcome.json
/// (job_protocol.hpp).
///
/// A job on several ranks (docs/many_machines.md, "Jobs on several ranks"): the process replaces itself by
/// the launcher (launcher.hpp), its stdout the progress pipe and its stderr the attempt's launcher.log,
/// keeping the signal that kills it with its parent. Each rank the launcher starts runs `stoss run-job`
/// again: rank 0 runs the attempt in its folder, reports progress on stdout (which the launcher passes on)
/// and writes outcome.json; rank k > 0 runs the same steps in a private folder. The parent cancels a launch
/// by writing the attempt's file `cancel` (job_protocol.hpp), which rank 0 looks for; the ranks stop at the
/// same step (parallel::on_any_rank).

#include <cstddef>
#include <filesystem>
#include <string>

#include "server/jobs/id.hpp"

namespace stoss::server::jobs {

struct JobProcessOptions {
  std::filesystem::path data;  ///< the server's --data directory
  JobId id;
  int attempt = 0;         ///< >= 1
  std::size_t memory = 0;  ///< RLIMIT_AS in bytes (0: none)
  long parent = 0;  ///< the parent's pid: a child whose parent is already gone does not run (0: unchecked)
  int ranks = 1;    ///< the MPI ranks of the job (solver.ranks): above 1, run under `launcher`
  std::string launcher;   ///< the launcher's template (launcher.hpp), for ranks > 1
  bool launched = false;  ///< one rank the launcher started (its place from the environment, mpi_place)
};

/// The file in the attempt's folder that takes the launcher's (and every rank's) stderr.
inline constexpr const char* launcher_log_file = "launcher.log";

/// Runs attempt `options.attempt` of job `options.id` in this process. Returns the exit code: 0 when it
/// wrote an outcome (whatever the job's fate), 3 when it cannot.
int run_job_process(const JobProcessOptions& options);

}  // namespace stoss::server::jobs
