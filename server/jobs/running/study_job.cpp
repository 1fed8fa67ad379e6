#include "server/jobs/running/study_job.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "core/simulate.hpp"
#include "server/jobs/reporting/job_observer.hpp"

namespace stoss::server::jobs {

namespace {

/// Where the sweep stands, from study::Options::run_finished.
struct Sweep {
  int runs = 0;
  int done = 0;
  int failed = 0;
  double wall_seconds = 0;  ///< of the runs done
  double reference_step = 0;
  double reference_wall_seconds = 0;
};

/// A study's progress: step/steps count runs, time/end are those of the run in progress, and the ETA
/// weighs the runs by their time steps (the reference run is the longest).
class StudyProgress {
 public:
  StudyProgress(const StudyContext& context, int runs, double total_steps)
      : context_(context), runs_(runs), total_steps_(total_steps), started_(context.clock.now()) {}

  /// The sink a run's ProgressObserver reports to.
  ProgressSink sink() {
    return [this](const Progress& p) { report(p.step, p.time, p.end); };
  }
  void run_done(int steps) {
    ++done_;
    steps_done_ += steps;
  }
  void finished(double end) { emit({done_, runs_, end, end, 0.0}); }

 private:
  void report(int run_step, double time, double end) { emit({done_, runs_, time, end, eta(run_step)}); }
  void emit(const Progress& p) {
    if (context_.progress) context_.progress(p);
  }
  std::optional<double> eta(int run_step) const {
    const double work = steps_done_ + run_step;
    if (work <= 0) return std::nullopt;
    const double elapsed = static_cast<double>(context_.clock.now() - started_) / 1000.0;
    return elapsed / work * std::max(0.0, total_steps_ - work);
  }

  const StudyContext& context_;
  int runs_;
  double total_steps_;
  Millis started_;
  int done_ = 0;
  double steps_done_ = 0;
};

void log_run(std::ostream& log, const Sweep& sweep, const study::Run& run, const model::Summary& summary,
             const std::string& failure) {
  log << "run " << sweep.done + 1 << "/" << sweep.runs << ": " << (run.reference ? "reference " : "")
      << model::to_string(run.scheme) << " h = " << run.step;
  if (run.tolerance > 0) log << " (first step), time.tolerance = " << run.tolerance;
  log << ": ";
  if (failure.empty())
    log << summary.steps << " steps, " << summary.wall_seconds << " s";
  else
    log << "failed after " << summary.steps << " steps: " << failure;
  log << '\n' << std::flush;
}

/// Counts a finished run into the sweep.
void record(Sweep& sweep, const study::Run& run, const model::Summary& summary, const std::string& failure) {
  if (run.reference) sweep.reference_wall_seconds = summary.wall_seconds;
  if (!run.reference && !(summary.completed && failure.empty())) ++sweep.failed;
  sweep.wall_seconds += summary.wall_seconds;
  ++sweep.done;
}

nlohmann::json study_summary(const Sweep& sweep) {
  return {{"completed", sweep.done == sweep.runs},
          {"runs", sweep.runs},
          {"runs_done", sweep.done},
          {"failed_runs", sweep.failed},
          {"reference_step", sweep.reference_step},
          {"reference_wall_seconds", sweep.reference_wall_seconds},
          {"wall_seconds", sweep.wall_seconds}};
}

Outcome canceled(const Sweep& sweep, std::ostream& log) {
  log << "canceled after " << sweep.done << " of " << sweep.runs << " runs\n" << std::flush;
  return {Status::canceled, study_summary(sweep), std::nullopt};
}

constexpr auto replace_invalid_utf8 = nlohmann::json::error_handler_t::replace;

}  // namespace

std::optional<model::Scheme> parse_scheme(std::string_view name) {
  return model::scheme_from_string(name);
}

nlohmann::json study_params_json(const study::Options& options) {
  nlohmann::json schemes = nlohmann::json::array();
  for (model::Scheme s : options.schemes) schemes.push_back(model::to_string(s));
  nlohmann::json params = {{"steps", options.steps},
                           {"schemes", schemes},
                           {"reference_step", options.reference_step},
                           {"repeat", options.repeat}};
  if (!options.tolerances.empty()) params["tolerances"] = options.tolerances;
  return params;
}

study::Options study_options(const nlohmann::json& params) {
  study::Options options;
  options.steps = params.at("steps").get<std::vector<double>>();
  options.schemes.clear();
  for (const auto& name : params.at("schemes")) {
    auto scheme = parse_scheme(name.get<std::string>());
    if (!scheme) throw std::invalid_argument("study: unknown scheme " + name.dump());
    options.schemes.push_back(*scheme);
  }
  options.reference_step = params.at("reference_step").get<double>();
  options.repeat = params.value("repeat", 1);  // a study queued before `repeat` ran each point once
  options.tolerances = params.value("tolerances", std::vector<double>{});
  return options;
}

int study_run_count(const study::Options& options) {
  return study::run_count(options);
}

study::Result study_result_from_json(const nlohmann::json& table) {
  return study::result_from_json(table);
}

Outcome run_study_job(const Job& job, const model::Model& model, const StudyContext& context) {
  if (!job.study) throw std::invalid_argument("study job " + job.id.str() + " has no study parameters");
  study::Options options = study_options(*job.study);
  const std::vector<study::Run> runs = study::plan(model, options);
  double total_steps = 0;
  for (const study::Run& run : runs) total_steps += run.steps;
  Sweep sweep{static_cast<int>(runs.size())};
  sweep.reference_step = study::resolved_reference_step(options);
  StudyProgress progress(context, sweep.runs, total_steps);
  std::unique_ptr<ProgressObserver> reporter;
  options.cancel = &context.cancel;
  options.observe_run = [&](const study::Run&) {
    reporter = std::make_unique<ProgressObserver>(progress.sink(), context.clock, context.progress_interval);
    return reporter.get();
  };
  options.run_finished = [&](const study::Run& run, const model::Summary& summary,
                             const std::string& failure) {
    if (context.cancel) return;
    log_run(context.log, sweep, run, summary, failure);
    record(sweep, run, summary, failure);
    progress.run_done(run.steps);
  };
  const study::Result result = study::run(model, options);
  if (result.canceled) return canceled(sweep, context.log);
  context.files.write_study(study::to_json(result).dump(-1, ' ', false, replace_invalid_utf8));
  progress.finished(model.time.end);
  context.log << "study completed: " << sweep.runs << " runs, " << sweep.failed << " failed, "
              << sweep.wall_seconds << " s\n"
              << std::flush;
  return {Status::succeeded, study_summary(sweep), std::nullopt};
}

}  // namespace stoss::server::jobs
