#pragma once
/// @file InProcessExecutor: runs one attempt of a job in the calling thread, writing only in the attempt's
/// folder (JobFiles::prepare_attempt): its log, a simulation's result (stoss::simulate, resumed from the
/// checkpoint seeded from the attempt before) or a study's table (study_job.hpp), and last outcome.json.
/// When an earlier attempt had completed its run but lost its lease before reporting it, that run's
/// outcome is adopted instead of running again.

#include <fstream>
#include <functional>

#include "core/model/model.hpp"
#include "server/jobs/clock.hpp"
#include "server/jobs/job_files.hpp"
#include "server/jobs/running/executor.hpp"

namespace stoss::server::jobs {

class InProcessExecutor : public Executor {
 public:
  /// `progress_interval`: least time between two progress reports (ms).
  InProcessExecutor(JobFiles files, const Clock& clock, Millis progress_interval = 500)
      : files_(std::move(files)), clock_(clock), progress_interval_(progress_interval) {}

  Outcome run(const Job& job, const std::atomic<bool>& cancel, const ProgressSink& progress) override;

  /// Called with the model once the attempt is set to run it (not when it adopts an earlier run or cannot
  /// load the scene): rank 0 of a launch prepares it for the ranks (job_process.cpp).
  void on_model(std::function<void(model::Model&)> prepare) { prepare_model_ = std::move(prepare); }

  /// Runs without writing result.h5 (rank k > 0 of a launch: rank 0 writes it; the checkpoints stay, and with
  /// them the steps that refresh the factorisation, so that every rank iterates alike).
  void without_result() { writes_result_ = false; }

  /// One simulation of the scene into `files` (result.h5 and result.xdmf, the checkpoint resumed from): what
  /// run does once the model is loaded, and what rank k > 0 of a launch does in its private folder.
  Outcome simulate_job(const Job& job, const AttemptFiles& files, const model::Model& model,
                       std::ofstream& log, const std::atomic<bool>& cancel, const ProgressSink& progress);

 private:
  /// An earlier attempt's completed run (result_attempt set), else a run of this attempt.
  Outcome adopt_or_run(const Job& job, const AttemptFiles& files, std::ofstream& log,
                       const std::atomic<bool>& cancel, const ProgressSink& progress);

  JobFiles files_;
  const Clock& clock_;
  Millis progress_interval_;
  std::function<void(model::Model&)> prepare_model_;
  bool writes_result_ = true;
};

}  // namespace stoss::server::jobs
