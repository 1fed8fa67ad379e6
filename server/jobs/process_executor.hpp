#pragma once
/// @file ProcessExecutor: every job in its own process. The worker thread spawns `stoss run-job DATA ID
/// --attempt N` (the same binary), which runs the attempt with an InProcessExecutor and writes what a job
/// writes (log, result, study table) into the attempt's folder, DIR/jobs/<id>/attempt-<n>/; the parent relays
/// its progress (JSON lines on fd 3) to the store, stops it on cancel (SIGTERM: it stops within a step and
/// reports canceled), kills it past the wall-time limit, and reads its outcome (outcome.json). A job process
/// that dies (a signal, a limit) fails that job alone, with the reason: the server, and every other job, go
/// on.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "server/jobs/clock.hpp"
#include "server/jobs/executor.hpp"
#include "server/jobs/job_files.hpp"

namespace stoss::server::jobs {

/// Limits of one job process.
struct ProcessLimits {
  Millis wall = 0;          ///< wall time of one attempt (0: none); a scene's solver.max_wall_seconds may lower it
  std::size_t memory = 0;   ///< RLIMIT_AS of the process in bytes (0: none)
  Millis stop_grace = 30'000;  ///< after SIGTERM (cancel, shutdown), how long before SIGKILL
};

class ProcessExecutor : public Executor {
 public:
  /// `binary`: the stoss executable to spawn (normally this very program, /proc/self/exe).
  ProcessExecutor(JobFiles files, std::filesystem::path data_dir, std::filesystem::path binary,
                  ProcessLimits limits = {});

  Outcome run(const Job& job, const std::atomic<bool>& cancel, const ProgressSink& progress) override;

  /// The wall-time limit of `job` in ms: the lower of `server_limit` and the scene's
  /// solver.max_wall_seconds (0: none).
  static Millis wall_limit(const Job& job, Millis server_limit);

 private:
  Outcome supervise(const Job& job, const std::atomic<bool>& cancel, const ProgressSink& progress);
  /// Ends an attempt that produced no outcome of its own: the reason goes to the log, partial files go.
  Outcome failed(const Job& job, const std::string& reason) const;

  JobFiles files_;
  std::filesystem::path data_dir_;
  std::filesystem::path binary_;
  ProcessLimits limits_;
};

/// Files of the protocol between the two processes, in the attempt's folder (and outcome.json,
/// outcome_file_name, how it ended, written by the child).
inline constexpr const char* job_request_file = "job.json";  ///< what the child runs
inline constexpr const char* job_pid_file = "process.pid";   ///< the child's pid while it runs
/// The child writes one JSON line per progress report to this descriptor.
inline constexpr int progress_fd = 3;

/// A job as the child reads it (id, kind, attempt, worker, scene, study), and back.
nlohmann::json job_request_json(const Job& job);
Job job_from_request(const nlohmann::json& request);

/// "killed by signal SIGSEGV".
std::string signal_reason(int signal);

/// `stoss run-job DATA_DIR JOB_ID --attempt N [--memory BYTES] [--parent PID]`: the child side (hidden
/// subcommand).
/// Exit 0 when it wrote an outcome (whatever the job's fate), 2 on a bad command line, 3 when it cannot.
int run_job_command(const std::vector<std::string>& args);

}  // namespace stoss::server::jobs
