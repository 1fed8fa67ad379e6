#pragma once
/// @file Observers a job adds to a run: throttled progress with an ETA, and the log file.

#include <fstream>
#include <optional>

#include "core/model/observer.hpp"
#include "server/jobs/clock.hpp"
#include "server/jobs/running/executor.hpp"

namespace stoss::server::jobs {

/// Reports progress (step, steps, simulated time, ETA) at most once per `interval`, and once at the end:
/// a run of thousands of steps per second costs a handful of store writes per second. With fixed steps the
/// ETA is the wall time per step times the steps to go. With time.tolerance the steps are not known ahead:
/// the fraction done is time/end, the ETA the wall time per unit of simulated time times end − time, and
/// `steps` the steps the run would take at its mean step so far (step · end/time), so that step/steps is
/// time/end; before the first step it is end/time.step.
class ProgressObserver : public model::Observer {
 public:
  ProgressObserver(ProgressSink sink, const Clock& clock, Millis interval = 500);

  void begin(const model::Model& model, const model::SeriesLayout& layout) override;
  void step(const model::StepRow& row) override;
  /// A run resumed from a checkpoint: the ETA counts from its step and this moment, not from the rows
  /// given back at once.
  void resumed(int step) override;
  void end(const model::Summary& summary) override;

  /// The latest progress, reported or not.
  const Progress& current() const { return current_; }

 private:
  void report(Millis now);
  /// The ETA and, with time.tolerance, the projected steps from the rate since started_.
  void estimate(Millis now);

  ProgressSink sink_;
  const Clock& clock_;
  Millis interval_;
  Millis started_ = 0;
  int first_step_ = 0;     ///< the step the rate counts from: 0, or the checkpoint's when resumed
  double first_time_ = 0;  ///< the simulated time at first_step_
  bool adaptive_ = false;  ///< time.tolerance: progress by simulated time
  std::optional<Millis> last_report_;
  Progress current_;
};

/// Appends the run's log lines to a file, flushed line by line (so a killed run leaves its log).
class LogObserver : public model::Observer {
 public:
  explicit LogObserver(std::ofstream& out) : out_(out) {}
  /// Notes whether the run counts external work (series/external_work): the energy line is then H − W_ext.
  void begin(const model::Model& model, const model::SeriesLayout& layout) override;
  void step(const model::StepRow& row) override;
  /// Solver lines ("newton: …") name the step they belong to and the time it starts from.
  void log(const std::string& line) override;
  void end(const model::Summary& summary) override;

 private:
  std::ofstream& out_;
  int last_step_ = -1;  ///< the last converged step (0: the initial state)
  double last_time_ = 0;
  bool external_work_ = false;  ///< the run has series/external_work (loads or prescribed motion)
  bool static_steps_ = false;   ///< time.scheme "static": no energy kept between load levels
};

/// The job summary of docs/api.md from a run's summary; max_penetration only when the model has contact,
/// external_work (the last value of series/external_work) only when it has loads or prescribed motion.
nlohmann::json summary_json(const model::Summary& summary, const model::Model& model);

}  // namespace stoss::server::jobs
