#pragma once
/// @file ProcessExecutor: every job in its own process (the parent side). The worker thread spawns
/// `stoss run-job DATA ID --attempt N` (the same binary; the child side is job_process.hpp, what passes
/// between them job_protocol.hpp), which runs the attempt with an InProcessExecutor and writes what a job
/// writes (log, result, study table) into the attempt's folder, DIR/jobs/<id>/attempt-<n>/; the parent relays
/// its progress to the store, stops it on cancel (SIGTERM: it stops within a step and reports canceled),
/// kills it past the wall-time limit, and reads its outcome (outcome.json). A job process that dies (a
/// signal, a limit) fails that job alone, with the reason: the server, and every other job, go on.
///
/// A simulation whose scene asks for solver.ranks > 1 runs under the launcher (job_process.hpp): the child
/// becomes the launcher, cancel is the attempt's file `cancel` (rank 0 looks for it), SIGKILL past the grace
/// or the limit kills the launcher and with it every rank on this machine, and a launch that ends without
/// an outcome fails with the launcher's own message (launcher.log).

#include <sys/types.h>

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "server/jobs/clock.hpp"
#include "server/jobs/job_files.hpp"
#include "server/jobs/running/executor.hpp"
#include "server/jobs/running/job_protocol.hpp"

namespace stoss::server::jobs {

/// Limits of one job process.
struct ProcessLimits {
  Millis wall = 0;  ///< wall time of one attempt (0: none); a scene's solver.max_wall_seconds may lower it
  std::size_t memory = 0;      ///< RLIMIT_AS of the process in bytes (0: none)
  Millis stop_grace = 30'000;  ///< after SIGTERM (cancel, shutdown), how long before SIGKILL
  std::string launcher;        ///< starts a job's ranks (launcher.hpp); empty: default_launcher
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
  /// The MPI ranks `job` runs on: its ranks (the scene's solver.ranks) for a simulation, else 1.
  static int ranks(const Job& job);

 private:
  /// What the parent did to a running child, and why it stopped watching.
  struct Watched {
    bool terminated = false;  ///< SIGTERM sent (cancel; to a launch, the cancel file written)
    bool killed = false;      ///< SIGKILL sent (grace over, or wall-time limit)
    bool over_time = false;   ///< killed for the wall-time limit
  };

  Outcome supervise(const Job& job, const std::atomic<bool>& cancel, const ProgressSink& progress);
  /// Starts `stoss run-job` for `job` with `write_end` as its progress_fd (closed here); returns its pid.
  pid_t spawn(const Job& job, int write_end) const;
  /// Relays the child's progress from `read_end` until it closes, enforcing cancel and the limits.
  /// `cancel_by_file`: for a launch, the file that cancels it (empty: SIGTERM cancels).
  Watched watch(pid_t pid, int read_end, Millis wall, const std::filesystem::path& cancel_by_file,
                const std::atomic<bool>& cancel, const ProgressSink& progress) const;
  /// How the attempt ended: from the child's exit `status` and what was done to it, else its outcome.json.
  Outcome ended(const Job& job, const std::filesystem::path& dir, const Watched& watched, int status,
                Millis wall) const;
  /// How an attempt on several ranks ended: its outcome.json, which rank 0 writes last, whatever the
  /// launcher's exit status; else the launcher's message.
  Outcome launch_ended(const Job& job, const std::filesystem::path& dir, const Watched& watched, int status,
                       Millis wall) const;
  /// Ends an attempt that produced no outcome of its own: the reason goes to the log, partial files go.
  Outcome failed(const Job& job, const std::string& reason) const;

  JobFiles files_;
  std::filesystem::path data_dir_;
  std::filesystem::path binary_;
  ProcessLimits limits_;
};

/// "killed by signal SIGSEGV".
std::string signal_reason(int signal);

}  // namespace stoss::server::jobs
