#pragma once
/// @file InProcessExecutor: runs a job in the calling thread (a worker of the pool), writing its log to
/// log.txt: a simulation (stoss::simulate, the result into the job's directory) or a study (the sweep of
/// study_job.hpp, the table into study.json).

#include <fstream>

#include "core/model/model.hpp"
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
  /// One simulation of the scene, its result written to result.h5 and result.xdmf.
  Outcome simulate_job(const Job& job, const model::Model& model, std::ofstream& log,
                       const std::atomic<bool>& cancel, const ProgressSink& progress);

  JobFiles files_;
  const Clock& clock_;
  Millis progress_interval_;
};

}  // namespace stoss::server::jobs
