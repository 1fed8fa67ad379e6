#include "server/jobs/running/inprocess_executor.hpp"

#include <fstream>
#include <optional>
#include <vector>

#include "core/output/result_writer.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"
#include "server/jobs/reporting/job_observer.hpp"
#include "server/jobs/reporting/series_recorder.hpp"
#include "server/jobs/running/study_job.hpp"

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
  std::optional<AttemptFiles> files;
  Outcome outcome;
  std::ofstream log;
  try {
    files = files_.prepare_attempt(job.id, job.attempt);
    log.open(files->log(), std::ios::app);
    log << "attempt " << job.attempt << " started " << format_rfc3339(clock_.now()) << " by "
        << job.worker.value_or("?") << '\n'
        << std::flush;
    outcome = adopt_or_run(job, *files, log, cancel, progress);
  } catch (const std::exception& e) {
    if (files) files->discard_partial();
    outcome = failed(log, e.what());
  } catch (...) {
    if (files) files->discard_partial();
    outcome = failed(log, "unknown error");
  }
  try {
    if (files) files->write_outcome(outcome);  // last: the attempt's files are final
    // Only now its checkpoint goes: an attempt started meanwhile finds the outcome, or else the checkpoint.
    if (files && outcome.status == Status::succeeded) files_.prune_through(job.id, job.attempt);
  } catch (const std::exception& e) {
    log << "cannot record the outcome: " << e.what() << '\n' << std::flush;
  }
  return outcome;
}

Outcome InProcessExecutor::adopt_or_run(const Job& job, const AttemptFiles& files, std::ofstream& log,
                                        const std::atomic<bool>& cancel, const ProgressSink& progress) {
  if (auto earlier = files_.completed_before(job.id, job.attempt)) {
    // An earlier attempt completed its run but lost its lease before it could report: its result stands.
    log << "attempt " << *earlier->result_attempt << " had completed the run; its result is adopted\n"
        << std::flush;
    return *earlier;
  }
  model::Model model = scene::load_resolved(job.scene, files_.mesh_files());  // validated at POST
  if (prepare_model_) prepare_model_(model);
  if (job.kind == Kind::study)
    return run_study_job(job, model, {files, clock_, progress_interval_, log, cancel, progress});
  return simulate_job(job, files, model, log, cancel, progress);
}

namespace {

/// The job summary of a run, with the friction balance when the run dissipates (frictional contact).
nlohmann::json job_summary(const model::Summary& summary, const model::Model& model,
                           const SeriesRecorder& series) {
  nlohmann::json j = summary_json(summary, model);
  if (auto dissipated = series.dissipated_energy()) {
    j["dissipated_energy"] = *dissipated;
    j["energy_plus_dissipated_drift"] = series.energy_plus_dissipated_drift().value_or(0.0);
  }
  return j;
}

}  // namespace

Outcome InProcessExecutor::simulate_job(const Job& job, const AttemptFiles& files, const model::Model& model,
                                        std::ofstream& log, const std::atomic<bool>& cancel,
                                        const ProgressSink& progress) {
  std::optional<model::Summary> summary;
  SeriesRecorder series(files.dir() / partial_series_file);
  try {
    std::optional<output::ResultWriter> writer;
    ProgressObserver reporter(progress, clock_, progress_interval_);
    LogObserver logger(log);
    // The series before the progress: a step the server has been told of is in the series stream.
    std::vector<model::Observer*> listeners{&series, &reporter, &logger};
    if (writes_result_) listeners.insert(listeners.begin(), &writer.emplace(files.dir()));
    model::ObserverList observers(listeners);
    const Checkpoints checkpoints{files.checkpoint(), true};
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
    std::filesystem::remove_all(files.checkpoint(), ignored);  // the same step would fail again
    if (!series.summary()) throw;
    files.discard_partial();
    return failed(log, e.what(), job_summary(*series.summary(), model, series));
  } catch (const std::exception& e) {
    if (!series.summary()) throw;
    // A step failed: the series and summary up to the last completed step stay readable.
    files.discard_partial();
    return failed(log, e.what(), job_summary(*series.summary(), model, series));
  }
  if (summary->completed) {
    std::error_code ignored;
    std::filesystem::remove(files.dir() / partial_series_file, ignored);  // result.h5 has it all
    return {Status::succeeded, job_summary(*summary, model, series), std::nullopt};
  }
  files.discard_partial();
  log << "canceled at step " << summary->steps << '\n' << std::flush;
  return {Status::canceled, job_summary(*summary, model, series), std::nullopt};
}

}  // namespace stoss::server::jobs
