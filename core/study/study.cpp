#include "core/study/study.hpp"

#include <algorithm>
#include <cstdio>
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

Outcome run_once(model::Model m, model::Scheme scheme, double step) {
  m.time.scheme = scheme;
  m.time.step = step;
  m.output.every = std::max(1, m.time.steps());
  FinalState last;
  Outcome out;
  try {
    out.summary = simulate(m, last);
  } catch (const std::exception& e) {
    out.failure = e.what();
  }
  out.final_position = last.position;
  return out;
}

double max_nodal_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  double worst = 0;
  for (Eigen::Index I = 0; I < a.size() / 3; ++I) worst = std::max(worst, (a.segment<3>(3 * I) - b.segment<3>(3 * I)).norm());
  return worst;
}

Row row_of(const Outcome& o, model::Scheme scheme, double step, const Eigen::VectorXd& reference) {
  Row r;
  r.scheme = model::to_string(scheme);
  r.step = step;
  r.steps = o.summary.steps;
  r.completed = o.summary.completed && o.failure.empty();
  r.failure = o.failure;
  r.displacement_error = r.completed ? max_nodal_distance(o.final_position, reference) : NAN;
  r.energy_error = o.summary.energy_drift;
  r.momentum_error = std::max(o.summary.linear_momentum_drift, o.summary.angular_momentum_drift);
  r.wall_seconds = o.summary.wall_seconds;
  r.newton_iterations = o.summary.newton_iterations;
  r.newton_per_step = o.summary.newton_iterations_per_step;
  return r;
}

}  // namespace

Result run(const model::Model& model, const Options& options) {
  if (options.steps.empty()) throw std::invalid_argument("study: no step sizes given");
  Result result;
  result.reference_step = options.reference_step > 0
                              ? options.reference_step
                              : *std::min_element(options.steps.begin(), options.steps.end()) / 32;
  const Outcome reference = run_once(model, options.reference_scheme, result.reference_step);
  if (!reference.failure.empty()) throw SolverError("study: the reference run failed: " + reference.failure);
  result.reference_wall_seconds = reference.summary.wall_seconds;
  for (model::Scheme scheme : options.schemes)
    for (double step : options.steps)
      result.rows.push_back(row_of(run_once(model, scheme, step), scheme, step, reference.final_position));
  return result;
}

std::string to_csv(const Result& result) {
  std::ostringstream out;
  out << "scheme,step,steps,completed,displacement_error,energy_error,momentum_error,wall_seconds,"
         "newton_iterations,newton_per_step\n";
  out.precision(6);
  for (const Row& r : result.rows)
    out << r.scheme << ',' << r.step << ',' << r.steps << ',' << (r.completed ? 1 : 0) << ','
        << r.displacement_error << ',' << r.energy_error << ',' << r.momentum_error << ',' << r.wall_seconds << ','
        << r.newton_iterations << ',' << r.newton_per_step << '\n';
  return out.str();
}

nlohmann::json to_json(const Result& result) {
  nlohmann::json rows = nlohmann::json::array();
  for (const Row& r : result.rows) {
    nlohmann::json j{{"scheme", r.scheme},           {"step", r.step},
                     {"steps", r.steps},             {"completed", r.completed},
                     {"energy_error", r.energy_error}, {"momentum_error", r.momentum_error},
                     {"wall_seconds", r.wall_seconds}, {"newton_iterations", r.newton_iterations},
                     {"newton_per_step", r.newton_per_step}};
    j["displacement_error"] = r.completed ? nlohmann::json(r.displacement_error) : nlohmann::json(nullptr);
    if (!r.failure.empty()) j["failure"] = r.failure;
    rows.push_back(j);
  }
  return {{"reference_step", result.reference_step},
          {"reference_wall_seconds", result.reference_wall_seconds},
          {"rows", rows}};
}

std::string to_markdown(const Result& result) {
  std::ostringstream out;
  out << "| scheme | h | displacement error | energy error | momentum error | wall s | Newton its/step |\n"
         "|---|---|---|---|---|---|---|\n";
  char line[256];
  for (const Row& r : result.rows) {
    if (r.completed)
      std::snprintf(line, sizeof line, "| %s | %g | %.2e | %.2e | %.2e | %.2f | %.1f |\n", r.scheme.c_str(), r.step,
                    r.displacement_error, r.energy_error, r.momentum_error, r.wall_seconds, r.newton_per_step);
    else
      std::snprintf(line, sizeof line, "| %s | %g | failed at step %d | | | %.2f | |\n", r.scheme.c_str(), r.step,
                    r.steps, r.wall_seconds);
    out << line;
  }
  return out.str();
}

}  // namespace stoss::study
