#pragma once
/// @file `stoss run-job`: the hidden subcommand ProcessExecutor spawns for one job attempt (the child side is
/// server/jobs/running/job_process.hpp).

#include <string>
#include <vector>

namespace stoss::cli {

/// `stoss run-job DATA_DIR JOB_ID --attempt N [--memory BYTES] [--parent PID]`. Exit 0 when it wrote an
/// outcome (whatever the job's fate), 2 on a bad command line, 3 when it cannot.
int run_job_command(const std::vector<std::string>& args);

}  // namespace stoss::cli
