#include "core/study/study.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "core/simulate.hpp"

namespace stoss::study {
namespace {

/// Keeps the positions of the last frame (simulate always writes the last step as a frame).
class FinalState : public model::Observer {
 public:
  void frame(const model::Frame& f) override { position = f.position; }
  Eigen::VectorXd position;
};

struct Outcome {
  model::Summary summary;
  Eigen::VectorXd final_position;
  std::string failure;
};

Outcome run_once(model::Model m, const Run& run, const Options& options) {
  const bool had_tolerance = m.time.adaptive();
  m.time.scheme = run.scheme;
  m.time.step = run.step;
  m.time.tolerance.reset();
  if (run.tolerance > 0) {
    m.time.tolerance = run.tolerance;
    if (!had_tolerance) m.time.min_step = run.step / 1024, m.time.max_step = m.time.end;  // the defaults
  }
  m.output.every = std::numeric_limits<int>::max();  // the first and the last frame
  m.output.interval.reset();
  FinalState last;
  model::Observer* extra = options.observe_run ? options.observe_run(run) : nullptr;
  model::ObserverList observers(extra ? std::vector<model::Observer*>{&last, extra}
                                      : std::vector<model::Observer*>{&last});
  Outcome out;
  try {
    out.summary = simulate(m, observers, options.cancel);
  } catch (const std::exception& e) {
    out.failure = e.what();
  }
  out.final_position = last.position;
  if (options.run_finished) options.run_finished(run, out.summary, out.failure);
  return out;
}

double max_nodal_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  if (a.size() != b.size()) return NAN;
  double worst = 0;
  for (Eigen::Index I = 0; I < a.size() / 3; ++I)
    worst = std::max(worst, (a.segment<3>(3 * I) - b.segment<3>(3 * I)).norm());
  return worst;
}

Row row_of(const Outcome& o, const Run& run, const Eigen::VectorXd& reference) {
  Row r;
  r.scheme = model::to_string(run.scheme);
  r.step = run.step;
  r.tolerance = run.tolerance;
  r.steps = o.summary.steps;
  r.completed = o.summary.completed && o.failure.empty();
  r.failure = o.failure;
  r.displacement_error = r.completed ? max_nodal_distance(o.final_position, reference) : NAN;
  r.energy_error = o.summary.energy_drift;
  // Only where the system is free (the run checked its momenta, docs/results.md "Verdict"): with
  // supports or gravity the momenta change by their impulse, which is no error.
  r.momentum_error = model::has_check(o.summary, "linear_momentum_drift")
                         ? std::max(o.summary.linear_momentum_drift, o.summary.angular_momentum_drift)
                         : NAN;
  r.wall_seconds = o.summary.wall_seconds;
  r.newton_iterations = o.summary.newton_iterations;
  r.newton_per_step = o.summary.newton_iterations_per_step;
  return r;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

bool canceled(const Options& options) {
  return options.cancel && options.cancel->load();
}

double number_or_nan(const nlohmann::json& j, const char* key) {
  auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : NAN;
}

}  // namespace

double resolved_reference_step(const Options& options) {
  if (options.reference_step > 0) return options.reference_step;
  return *std::min_element(options.steps.begin(), options.steps.end()) / 32;
}

std::vector<Run> plan(const model::Model& model, const Options& options) {
  const auto steps_to_end = [&](double h) {
    model::TimeSpec t = model.time;
    t.step = h;
    return t.steps();
  };
  const double reference = resolved_reference_step(options);
  std::vector<Run> runs{{options.reference_scheme, reference, 0, true, steps_to_end(reference)}};
  for (model::Scheme scheme : options.schemes) {
    for (double step : options.steps)
      for (int k = 0; k < std::max(1, options.repeat); ++k)
        runs.push_back({scheme, step, 0, false, steps_to_end(step), k});
    for (double tolerance : options.tolerances)
      for (int k = 0; k < std::max(1, options.repeat); ++k)
        runs.push_back({scheme, model.time.step, tolerance, false, steps_to_end(model.time.step), k});
  }
  return runs;
}

int run_count(const Options& options) {
  const std::size_t points = options.schemes.size() * (options.steps.size() + options.tolerances.size());
  return 1 + static_cast<int>(points) * std::max(1, options.repeat);
}

Result run(const model::Model& model, const Options& options) {
  if (options.steps.empty()) throw std::invalid_argument("study: no step sizes given");
  for (double tolerance : options.tolerances)
    if (!(tolerance > 0) || !std::isfinite(tolerance))
      throw std::invalid_argument("study: a tolerance must be > 0 and finite");
  Result result;
  result.reference_step = resolved_reference_step(options);
  result.repeat = std::max(1, options.repeat);
  Eigen::VectorXd reference_position;
  for (const Run& r : plan(model, options)) {
    const Outcome o = run_once(model, r, options);
    if (canceled(options)) {
      result.canceled = true;
      return result;
    }
    if (!r.reference) {
      if (r.repetition == 0) result.rows.push_back(row_of(o, r, reference_position));
      Row& row = result.rows.back();
      row.wall_seconds_runs.push_back(o.summary.wall_seconds);
      row.wall_seconds = median(row.wall_seconds_runs);
      continue;
    }
    if (!o.failure.empty()) throw SolverError("study: the reference run failed: " + o.failure);
    reference_position = o.final_position;
    result.reference_wall_seconds = o.summary.wall_seconds;
  }
  return result;
}

std::string to_csv(const Result& result) {
  std::ostringstream out;
  // The column tolerance only when a row has one: tables of fixed steps keep their columns.
  const bool tolerances =
      std::any_of(result.rows.begin(), result.rows.end(), [](const Row& r) { return r.tolerance > 0; });
  out << "scheme,step,steps,completed,displacement_error,energy_error,momentum_error,wall_seconds,"
         "newton_iterations,newton_per_step"
      << (tolerances ? ",tolerance\n" : "\n");
  out.precision(6);
  for (const Row& r : result.rows) {
    out << r.scheme << ',' << r.step << ',' << r.steps << ',' << (r.completed ? 1 : 0) << ','
        << r.displacement_error << ',' << r.energy_error << ',' << r.momentum_error << ',' << r.wall_seconds
        << ',' << r.newton_iterations << ',' << r.newton_per_step;
    if (tolerances) out << ',' << (r.tolerance > 0 ? std::to_string(r.tolerance) : "");
    out << '\n';
  }
  return out.str();
}

nlohmann::json to_json(const Result& result) {
  nlohmann::json rows = nlohmann::json::array();
  for (const Row& r : result.rows) {
    nlohmann::json j{{"scheme", r.scheme},
                     {"step", r.step},
                     {"steps", r.steps},
                     {"completed", r.completed},
                     {"energy_error", r.energy_error},
                     {"momentum_error", r.momentum_error},
                     {"wall_seconds", r.wall_seconds},
                     {"wall_seconds_runs", r.wall_seconds_runs},
                     {"newton_iterations", r.newton_iterations},
                     {"newton_per_step", r.newton_per_step}};
    j["displacement_error"] = r.completed ? nlohmann::json(r.displacement_error) : nlohmann::json(nullptr);
    if (!r.failure.empty()) j["failure"] = r.failure;
    if (r.tolerance > 0) j["tolerance"] = r.tolerance;
    rows.push_back(j);
  }
  return {{"reference_step", result.reference_step},
          {"reference_wall_seconds", result.reference_wall_seconds},
          {"repeat", result.repeat},
          {"timing", timing_note(result)},
          {"rows", rows}};
}

Result result_from_json(const nlohmann::json& table) {
  Result result;
  result.reference_step = number_or_nan(table, "reference_step");
  result.reference_wall_seconds = number_or_nan(table, "reference_wall_seconds");
  result.repeat = table.value("repeat", 1);
  for (const auto& j : table.at("rows")) {
    Row r;
    r.scheme = j.value("scheme", "");
    r.step = number_or_nan(j, "step");
    r.tolerance = j.value("tolerance", 0.0);
    r.steps = j.value("steps", 0);
    r.completed = j.value("completed", false);
    r.failure = j.value("failure", "");
    r.displacement_error = number_or_nan(j, "displacement_error");
    r.energy_error = number_or_nan(j, "energy_error");
    r.momentum_error = number_or_nan(j, "momentum_error");
    r.wall_seconds = number_or_nan(j, "wall_seconds");
    // A table written before the runs were kept has the median alone.
    if (auto runs = j.find("wall_seconds_runs"); runs != j.end() && runs->is_array())
      for (const auto& w : *runs) r.wall_seconds_runs.push_back(w.is_number() ? w.get<double>() : NAN);
    r.newton_iterations = j.value("newton_iterations", 0);
    r.newton_per_step = number_or_nan(j, "newton_per_step");
    result.rows.push_back(r);
  }
  return result;
}

std::string timing_note(const Result& result) {
  return result.repeat > 1 ? "wall seconds: the median of " + std::to_string(result.repeat) + " runs"
                           : "wall seconds: one run";
}

std::string to_markdown(const Result& result) {
  std::ostringstream out;
  out << timing_note(result) << " of each scheme and step\n\n";
  out << "| scheme | h | displacement error | energy error | momentum error | wall s | Newton its/step |\n"
         "|---|---|---|---|---|---|---|\n";
  char line[320], h[64];
  for (const Row& r : result.rows) {
    if (r.tolerance > 0)  // steps chosen by a tolerance: the steps taken stand beside it
      std::snprintf(h, sizeof h, "TOL %g (%d steps)", r.tolerance, r.steps);
    else
      std::snprintf(h, sizeof h, "%g", r.step);
    if (r.completed)
      std::snprintf(line, sizeof line, "| %s | %s | %.2e | %.2e | %.2e | %.2f | %.1f |\n", r.scheme.c_str(),
                    h, r.displacement_error, r.energy_error, r.momentum_error, r.wall_seconds,
                    r.newton_per_step);
    else
      std::snprintf(line, sizeof line, "| %s | %s | failed at step %d | | | %.2f | |\n", r.scheme.c_str(), h,
                    r.steps, r.wall_seconds);
    out << line;
  }
  return out.str();
}

}  // namespace stoss::study
