#include "server/jobs/inprocess_executor.hpp"

#include <fstream>

#include "core/output/result_writer.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"
#include "server/jobs/job_observer.hpp"
#include "server/jobs/study_job.hpp"

namespace stoss::server::jobs {

namespace {

Outcome failed(std::ofstream& log, const std::string& reason) {
  log << "failed: " << reason << '\n' << std::flush;
  return {Status::failed, std::nullopt, reason};
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
    const model::Model model = scene::load(job.scene);
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

Outcome InProcessExecutor::simulate_job(const Job& job, const model::Model& model, std::ofstream& log,
                                        const std::atomic<bool>& cancel, const ProgressSink& progress) {
  std::optional<model::Summary> summary;
  {
    output::ResultWriter writer(files_.dir(job.id));
    ProgressObserver reporter(progress, clock_, progress_interval_);
    LogObserver logger(log);
    model::ObserverList observers({&writer, &reporter, &logger});
    summary = stoss::simulate(model, observers, &cancel);
  }
  if (summary->completed) return {Status::succeeded, summary_json(*summary, model), std::nullopt};
  files_.discard_partial(job.id);
  log << "canceled at step " << summary->steps << '\n' << std::flush;
  return {Status::canceled, summary_json(*summary, model), std::nullopt};
}

}  // namespace stoss::server::jobs
