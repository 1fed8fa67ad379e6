#pragma once
/// @file InProcessExecutor: runs stoss::simulate in the calling thread (a worker of the pool), writing
/// the result into the job's directory and its log to log.txt.

#include "server/jobs/clock.hpp"
#include "server/jobs/executor.hpp"
#include "server/jobs/job_files.hpp"

namespace stoss::server::jobs {

class InProcessExecutor : public Executor {
 public:
  /// `progress_interval`: least time between two progress reports (ms).
  InProcessExecutor(JobFiles files, const Clock& clock, Millis progress_interval = 500)
      : files_(std::move(files)), clock_(clock), progress_interval_(progress_interval) {}

  Outcome run(const Job& job, const std::atomic<bool>& cancel, const ProgressSink& progress) override;

 private:
  JobFiles files_;
  const Clock& clock_;
  Millis progress_interval_;
};

}  // namespace stoss::server::jobs
