#pragma once
/// @file What accuracy costs in time: one scene run with several schemes and step sizes, each compared
/// with a fine reference run.

#include <atomic>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/model/model.hpp"
#include "core/model/observer.hpp"

namespace stoss::study {

/// One run of a sweep: the reference first, then every scheme × step.
struct Run {
  model::Scheme scheme = model::Scheme::energy_momentum;
  double step = 0;       ///< the fixed step, or with a tolerance the first step
  double tolerance = 0;  ///< > 0: steps chosen by time.tolerance = this (docs/scene.md "Time")
  bool reference = false;
  int steps = 0;       ///< time steps to reach the scene's end (with a tolerance: at the first step)
  int repetition = 0;  ///< 0 … Options::repeat − 1: the same run again, for its wall time
};

struct Row;

struct Options {
  std::vector<model::Scheme> schemes{model::Scheme::energy_momentum, model::Scheme::midpoint,
                                     model::Scheme::hht};
  std::vector<double> steps;  ///< step sizes to sweep
  /// time.tolerance values to sweep beside the steps, each scheme once per value: the first step is the
  /// scene's time.step, min_step and max_step the scene's (or their defaults step/1024 and end).
  std::vector<double> tolerances;
  double reference_step = 0;  ///< 0: smallest step / 32
  model::Scheme reference_scheme = model::Scheme::energy_momentum;
  /// Runs of each scheme × step; the row's wall_seconds is their median (wall time is noisy on a shared
  /// machine; everything else a run reports is the same each time). The reference runs once.
  int repeat = 3;
  /// Set from any thread to stop the sweep inside the run in progress.
  const std::atomic<bool>* cancel = nullptr;
  /// Before each run: an observer to attach to it (e.g. a job's progress), or nullptr.
  std::function<model::Observer*(const Run&)> observe_run;
  /// After each run, with its summary and, if it threw, the failure.
  std::function<void(const Run&, const model::Summary&, const std::string& failure)> run_finished;
};

/// One run of the sweep.
struct Row {
  std::string scheme;
  double step = 0;  ///< the fixed step, or with a tolerance the first step
  int steps = 0;
  bool completed = false;
  std::string failure;            ///< why the run stopped, when it did not complete
  double displacement_error = 0;  ///< max over nodes |x(T) − x_ref(T)| at the end time T
  double energy_error = 0;        ///< max over steps |H_n − H_0| / |H_0|
  double momentum_error =
      0;  ///< max of the relative linear and angular momentum drifts; NaN (null) where the system is not free
  double wall_seconds = 0;  ///< the median of wall_seconds_runs
  int newton_iterations = 0;
  double newton_per_step = 0;
  double tolerance = 0;  ///< > 0: a run with steps chosen by this time.tolerance (step: its first step)
  /// The wall seconds of each of the Result::repeat runs of this point, in run order (wall time is noisy
  /// on a shared machine: the spread shows how much). Last, so that rows built field by field keep their
  /// order.
  std::vector<double> wall_seconds_runs;
};

struct Result {
  bool canceled = false;  ///< stopped by Options::cancel; rows holds the runs done
  double reference_step = 0;
  double reference_wall_seconds = 0;
  int repeat = 1;  ///< runs behind each row's wall_seconds (their median)
  std::vector<Row> rows;
};

/// How the rows' wall seconds were measured, for a reader: "wall seconds: the median of 3 runs".
std::string timing_note(const Result& result);

/// The runs of a sweep of `model` in order, reference first (reference_step resolved), each other run
/// options.repeat times in a row.
std::vector<Run> plan(const model::Model& model, const Options& options);
/// The runs plan() makes, without a model: the reference plus options.repeat per scheme × (step or
/// tolerance).
int run_count(const Options& options);
/// The reference step options.reference_step resolves to (smallest step / 32 when 0).
double resolved_reference_step(const Options& options);

/// Runs the reference and then every scheme × step and scheme × tolerance of `options` on `model` (its own
/// scheme, step and tolerance are replaced; everything else is kept). A run that fails is a row with
/// completed = false.
Result run(const model::Model& model, const Options& options);

std::string to_csv(const Result& result);
nlohmann::json to_json(const Result& result);
/// The inverse of to_json (a null error reads as NaN).
Result result_from_json(const nlohmann::json& table);
/// A Markdown table, as docs/measurements.md shows it.
std::string to_markdown(const Result& result);

}  // namespace stoss::study
