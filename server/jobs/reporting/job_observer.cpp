#include "server/jobs/reporting/job_observer.hpp"

#include <algorithm>
#include <cmath>

#include "core/run/series_table.hpp"
#include "core/scene/estimates.hpp"

namespace stoss::server::jobs {

ProgressObserver::ProgressObserver(ProgressSink sink, const Clock& clock, Millis interval)
    : sink_(std::move(sink)), clock_(clock), interval_(interval) {}

void ProgressObserver::begin(const model::Model& model, const model::SeriesLayout&) {
  started_ = clock_.now();
  adaptive_ = model.time.adaptive();
  // Until a step is measured, the ETA is the estimate made before the run (scene/estimates.hpp, W7).
  current_ = Progress{0, model.time.steps(), 0.0, model.time.end, scene::estimate(model).wall_seconds};
  report(started_);
}

void ProgressObserver::step(const model::StepRow& row) {
  current_.step = row.step;
  current_.time = row.time;
  const Millis now = clock_.now();
  estimate(now);
  if (!last_report_ || now - *last_report_ >= interval_) report(now);
}

void ProgressObserver::estimate(Millis now) {
  const double elapsed = static_cast<double>(now - started_) / 1000.0;
  if (!adaptive_) {
    if (current_.step > first_step_)
      current_.eta_seconds =
          elapsed / (current_.step - first_step_) * std::max(0, current_.steps - current_.step);
    return;
  }
  if (current_.time <= 0 || current_.time <= first_time_) return;
  current_.steps =
      std::max(current_.step, static_cast<int>(std::lround(current_.step * current_.end / current_.time)));
  current_.eta_seconds =
      elapsed / (current_.time - first_time_) * std::max(0.0, current_.end - current_.time);
}

void ProgressObserver::resumed(int step) {
  started_ = clock_.now();
  first_step_ = step;
  first_time_ = current_.time;
  current_.eta_seconds.reset();
}

void ProgressObserver::end(const model::Summary&) {
  if (adaptive_ ? current_.time >= current_.end : current_.step >= current_.steps) current_.eta_seconds = 0.0;
  report(clock_.now());
}

void ProgressObserver::report(Millis now) {
  last_report_ = now;
  if (sink_) sink_(current_);
}

void LogObserver::begin(const model::Model& model, const model::SeriesLayout& layout) {
  external_work_ = layout.index_of("external_work") >= 0;
  static_steps_ = model.time.scheme == model::Scheme::equilibrium;
}

void LogObserver::step(const model::StepRow& row) {
  last_step_ = row.step;
  last_time_ = row.time;
}

void LogObserver::log(const std::string& line) {
  if (last_step_ >= 0 && line.rfind("newton:", 0) == 0)
    out_ << "step " << last_step_ + 1 << " (from t = " << last_time_ << "): ";
  out_ << line << '\n' << std::flush;
}

void LogObserver::end(const model::Summary& s) {
  out_ << (s.completed ? "run completed: " : "run stopped: ") << s.steps << " steps, t = " << s.end_time;
  if (static_steps_)
    out_ << ", energy drift not reported (static load steps)";
  else
    out_ << (external_work_ ? ", energy drift (H − W_ext) " : ", energy drift ") << s.energy_drift;
  if (external_work_) out_ << ", external work " << s.external_work;
  out_ << ", " << s.newton_iterations << " Newton iterations, " << s.wall_seconds << " s, verdict "
       << s.verdict << "\n";
  for (const model::Check& c : s.checks)
    if (!c.passed) out_ << "warning: check " << c.name << " failed: " << c.value << " > " << c.bound << "\n";
  out_ << std::flush;
}

nlohmann::json summary_json(const model::Summary& s, const model::Model& model) {
  nlohmann::json j = {{"completed", s.completed},
                      {"steps", s.steps},
                      {"end_time", s.end_time},
                      {"initial_energy", s.initial_energy},
                      {"energy_drift", s.energy_drift},
                      {"linear_momentum_drift", s.linear_momentum_drift},
                      {"angular_momentum_drift", s.angular_momentum_drift},
                      {"newton_iterations", s.newton_iterations},
                      {"newton_iterations_per_step", s.newton_iterations_per_step},
                      {"wall_seconds", s.wall_seconds},
                      {"linear_solver_seconds", s.linear_solver_seconds},
                      {"linear_factorization_seconds", s.linear_factorization_seconds},
                      {"linear_solve_seconds", s.linear_solve_seconds},
                      {"assembly_seconds", s.assembly_seconds},
                      {"contact_seconds", s.contact_seconds},
                      {"output_seconds", s.output_seconds},
                      {"peak_memory_mb", s.peak_memory_bytes / 1e6},
                      {"verdict", s.verdict},
                      {"checks", model::checks_json(s.checks)}};
  if (!model.contact.empty()) j["max_penetration"] = s.max_penetration;
  if (stoss::run::is_present(stoss::run::Presence::loads, model)) j["external_work"] = s.external_work;
  if (s.resumed_from_step > 0) j["resumed_from_step"] = s.resumed_from_step;
  if (s.krylov_iterations_per_solve > 0) {  // a Krylov path (solver.linear iterative, petsc_gamg) ran
    j["krylov_iterations_per_solve"] = s.krylov_iterations_per_solve;
    j["krylov_fallbacks"] = s.krylov_fallbacks;
  }
  return j;
}

}  // namespace stoss::server::jobs
