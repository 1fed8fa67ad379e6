#include "server/jobs/inprocess_executor.hpp"

#include <fstream>

#include "core/output/result_writer.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"
#include "server/jobs/job_observer.hpp"
#include "server/jobs/series_recorder.hpp"
#include "server/jobs/study_job.hpp"

namespace stoss::server::jobs {

namespace {

Outcome failed(std::ofstream& log, const std::string& reason,
               std::optional<nlohmann::json> summary = std::nullopt) {
  log << "failed: " << reason << '\n' << std::flush;
  return {Status::failed, std::move(summary), reason};
}

}  // namespace

Outcome InProcessExecutor::run(const Job& job, const std::atomic<bool>& cancel,
                               const ProgressSink& progress) {
  std::ofstream log;
  try {
    files_.prepare_attempt(job.id);
    log.open(files_.log(job.id), std::ios::app);
    log << "attempt " << job.attempt << " started " << format_rfc3339(clock_.now()) << " by "
        << job.worker.value_or("?") << '\n'
        << std::flush;
    const model::Model model = scene::load_resolved(job.scene, files_.mesh_files());  // validated at POST
    if (job.kind == Kind::study)
      return run_study_job(job, model, {files_, clock_, progress_interval_, log, cancel, progress});
    return simulate_job(job, model, log, cancel, progress);
  } catch (const std::exception& e) {
    files_.discard_partial(job.id);
    return failed(log, e.what());
  } catch (...) {
    files_.discard_partial(job.id);
    return failed(log, "unknown error");
  }
}

namespace {

/// The job summary of a run, with the friction balance when the run dissipates (frictional contact).
nlohmann::json job_summary(const model::Summary& summary, const model::Model& model, const SeriesRecorder& series) {
  nlohmann::json j = summary_json(summary, model);
  if (auto dissipated = series.dissipated_energy()) {
    j["dissipated_energy"] = *dissipated;
    j["energy_plus_dissipated_drift"] = series.energy_plus_dissipated_drift().value_or(0.0);
  }
  return j;
}

}  // namespace

Outcome InProcessExecutor::simulate_job(const Job& job, const model::Model& model, std::ofstream& log,
                                        const std::atomic<bool>& cancel, const ProgressSink& progress) {
  std::optional<model::Summary> summary;
  SeriesRecorder series(files_.dir(job.id) / partial_series_file);
  try {
    output::ResultWriter writer(files_.dir(job.id));
    ProgressObserver reporter(progress, clock_, progress_interval_);
    LogObserver logger(log);
    model::ObserverList observers({&writer, &reporter, &logger, &series});
    const Checkpoints checkpoints{files_.checkpoint(job.id), true};
    try {
      summary = stoss::simulate(model, observers, &cancel, checkpoints);
    } catch (const CheckpointError& e) {  // nothing was reported yet: start over without it
      log << e.what() << "; starting from step 0\n" << std::flush;
      std::error_code ignored;
      std::filesystem::remove_all(checkpoints.directory, ignored);
      summary = stoss::simulate(model, observers, &cancel, checkpoints);
    }
  } catch (const SolverError& e) {
    std::error_code ignored;
    std::filesystem::remove_all(files_.checkpoint(job.id), ignored);  // the same step would fail again
    if (!series.summary()) throw;
    files_.discard_partial(job.id);
    return failed(log, e.what(), job_summary(*series.summary(), model, series));
  } catch (const std::exception& e) {
    if (!series.summary()) throw;
    // A step failed: the series and summary up to the last completed step stay readable.
    files_.discard_partial(job.id);
    return failed(log, e.what(), job_summary(*series.summary(), model, series));
  }
  if (summary->completed) {
    std::error_code ignored;
    std::filesystem::remove(files_.dir(job.id) / partial_series_file, ignored);  // result.h5 has it all
    std::filesystem::remove_all(files_.checkpoint(job.id), ignored);
    return {Status::succeeded, job_summary(*summary, model, series), std::nullopt};
  }
  files_.discard_partial(job.id);
  log << "canceled at step " << summary->steps << '\n' << std::flush;
  return {Status::canceled, job_summary(*summary, model, series), std::nullopt};
}

}  // namespace stoss::server::jobs
