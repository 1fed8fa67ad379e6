#pragma once
/// @file The child side of ProcessExecutor: the process of one job attempt (`stoss run-job`, parsed in
/// server/cli/run_job.hpp). It dies with its parent, honours SIGTERM as a cancel within a step, runs the
/// attempt with an InProcessExecutor, relays progress on progress_fd and writes outcome.json
/// (job_protocol.hpp).

#include <cstddef>
#include <filesystem>

#include "server/jobs/id.hpp"

namespace stoss::server::jobs {

struct JobProcessOptions {
  std::filesystem::path data;  ///< the server's --data directory
  JobId id;
  int attempt = 0;         ///< >= 1
  std::size_t memory = 0;  ///< RLIMIT_AS in bytes (0: none)
  long parent = 0;  ///< the parent's pid: a child whose parent is already gone does not run (0: unchecked)
};

/// Runs attempt `options.attempt` of job `options.id` in this process. Returns the exit code: 0 when it
/// wrote an outcome (whatever the job's fate), 3 when it cannot.
int run_job_process(const JobProcessOptions& options);

}  // namespace stoss::server::jobs
