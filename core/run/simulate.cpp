#include "core/run/simulate.hpp"

#include <algorithm>
#include <optional>
#include <sstream>

#include "core/run/checkpoint_schedule.hpp"
#include "core/run/checks.hpp"
#include "core/run/measures.hpp"
#include "core/run/problem.hpp"
#include "core/run/recorder.hpp"
#include "core/run/series_table.hpp"
#include "core/run/solver_choice.hpp"
#include "core/run/timing.hpp"
#include "core/time/integrator.hpp"
#include "core/time/step_reduction.hpp"

namespace stoss {
namespace {

using namespace run;

/// Most halvings of a step whose Newton solve fails (time/step_reduction.hpp): substeps down to h/16.
constexpr int max_step_halvings = 4;

std::string failure_message(int step, double t, double h, const time::ReducedStep& r) {
  std::ostringstream out;
  out << "step " << step + 1 << " (t = " << t << " → " << t + h << ") did not converge: " << r.failure
      << "; residual history: " << solve::format_history(r.residuals)
      << ". Hint: reduce time.step, or check the material and initial velocities.";
  return out.str();
}

std::optional<CheckpointStore> open_store(const Checkpoints& checkpoints) {
  if (checkpoints.directory.empty()) return std::nullopt;
  return CheckpointStore(checkpoints.directory);
}

/// One run from its start (or checkpoint) to its end: what simulate() drives step by step.
class Run {
 public:
  Run(const model::Model& m, model::Observer& observer, const Checkpoints& checkpoints)
      : m_(m),
        observer_(observer),
        problem_(build_problem(m)),
        terms_(problem_.terms()),
        integrator_(problem_.mass, terms_, problem_.fixed, time::make_scheme(m.time), newton_options(m),
                    problem_.length_scale, problem_.total_mass),
        s_(initial_state(m, problem_)),
        store_(open_store(checkpoints)),
        recorder_(observer, store_ ? &*store_ : nullptr, problem_),
        series_(m),
        schedule_(m.output) {
    integrator_.set_velocity_map(problem_.velocity_map);
    integrator_.initialize(s_);
    if (store_ && checkpoints.resume && store_->exists()) resumed_ = load_checkpoint(*store_, m, terms_);
  }

  int first_step() const { return s_.step + 1; }
  int steps() const { return steps_; }

  /// Tells the observer of the run, then gives it step 0, or the rows and frames up to the checkpoint.
  void begin() {
    const auto t_out = Clock::now();
    observer_.begin(m_, series_.layout());
    if (m_.solver.linear != model::LinearSolver::direct) observer_.log(linear_solver_line(m_));
    b0_ = balance(problem_, s_);  // the initial state, also when resuming: the drifts are against it
    if (resumed_) {
      resume(*resumed_);
    } else {
      const ContactRow c = contact_row(problem_, nullptr);
      recorder_.step(series_.row(s_.step, s_.t, {b0_, c, nullptr, 0.0}));
      recorder_.frame(0, frame_of(s_, problem_));
    }
    output_seconds_ += seconds_since(t_out);
    sum_.initial_energy = b0_.total();
  }

  /// Solves step n (halving it when Newton fails), reports it, and keeps a checkpoint when one is due.
  /// @throws SolverError when the step cannot be solved, after observer.end.
  void advance(int n) {
    const double h = std::min(m_.time.step, m_.time.end - s_.t);
    const auto t0 = Clock::now();
    const int step0 = s_.step;
    const double time0 = s_.t;
    ContactRow c;
    const auto log = [&](const std::string& line) { observer_.log(line); };
    const time::ReducedStep r = time::step_with_reduction(integrator_, s_, h, max_step_halvings, log, [&] {
      add_substep(c, contact_row(problem_, &integrator_));
    });
    if (!r.converged) {
      const std::string message = failure_message(step0, time0, h, r);
      observer_.log(message);
      finish(false);
      throw SolverError(message);
    }
    sum_.newton_iterations += r.iterations;
    if (r.substeps > 1) ++sum_.reduced_steps;
    const auto t_out = Clock::now();
    const Balance b = balance(problem_, s_);
    update_summary(sum_, b0_, b, c);
    recorder_.step(series_.row(s_.step, s_.t, {b, c, &r, seconds_since(t0)}));
    if (m_.output.frame_due(n, steps_)) recorder_.frame(n, frame_of(s_, problem_));
    keep_checkpoint(n);
    output_seconds_ += seconds_since(t_out);
  }

  /// The summary, told to the observer (observer.end).
  model::Summary finish(bool completed) {
    sum_.completed = completed;
    sum_.steps = s_.step;
    sum_.end_time = s_.t;
    sum_.newton_iterations_per_step = s_.step > 0 ? double(sum_.newton_iterations) / s_.step : 0.0;
    add_timing();
    report_linear_solver();
    add_verdict(m_, sum_);
    observer_.end(sum_);
    return sum_;
  }

 private:
  void resume(const Checkpoint& c) {
    recorder_.replay(c);
    s_ = c.state;
    for (size_t k = 0; k < terms_.size(); ++k) terms_[k]->restore_state(c.terms[k].second, s_.x, s_.v);
    sum_ = c.summary;
    sum_.resumed_from_step = s_.step;
    observer_.resumed(s_.step);
    observer_.log("resumed from step " + std::to_string(s_.step) + " (t = " + std::to_string(s_.t) +
                  ") of the checkpoint " + store_->state_file().string() + ": computing steps " +
                  std::to_string(s_.step + 1) + " to " + std::to_string(steps_));
  }

  void keep_checkpoint(int n) {
    if (!store_ || !schedule_.may_land(n, steps_)) return;
    if (schedule_.due(n, steps_)) {
      store_->write(checkpoint_of(m_, s_, terms_, sum_, recorder_));
      schedule_.written();
    }
    integrator_.forget_factorization();  // the next step as a run resumed from here computes it
  }

  /// Where the wall time went (model::Summary): terms in integrator order, elasticity and gravity as
  /// assembly, the contact pairs as contact.
  void add_timing() {
    sum_.wall_seconds = seconds_since(wall0_);
    sum_.linear_factorization_seconds = integrator_.linear_factorization_seconds();
    sum_.linear_solve_seconds = integrator_.linear_solve_seconds();
    sum_.linear_solver_seconds = sum_.linear_factorization_seconds + sum_.linear_solve_seconds;
    sum_.assembly_seconds = problem_.setup_seconds + integrator_.inertia_seconds();
    sum_.contact_seconds = problem_.setup_contact_seconds;
    for (size_t k = 0; k < terms_.size(); ++k)
      (k < problem_.first_contact_term() ? sum_.assembly_seconds : sum_.contact_seconds) +=
          integrator_.term_seconds(k);
    sum_.output_seconds = output_seconds_;
    sum_.peak_memory_bytes = peak_resident_bytes();
  }

  void report_linear_solver() {
    const solve::LinearSolver& linear = integrator_.linear_solver();
    if (linear.krylov_solves() > 0)
      sum_.krylov_iterations_per_solve = double(linear.krylov_iterations()) / double(linear.krylov_solves());
    sum_.krylov_fallbacks = int(linear.krylov_fallbacks());
    if (linear.krylov_solves() > 0) observer_.log(krylov_line(linear));
    if (!linear.preconditioner_description().empty())
      observer_.log("linear solver: " + linear.preconditioner_description());
  }

  const model::Model& m_;
  model::Observer& observer_;
  const Clock::time_point wall0_ = Clock::now();  // before the problem is built: set first
  Problem problem_;
  std::vector<time::Term*> terms_;
  time::Integrator integrator_;
  time::State s_;
  std::optional<CheckpointStore> store_;
  std::optional<Checkpoint> resumed_;
  Recorder recorder_;
  const SeriesRows series_;
  CheckpointSchedule schedule_;
  const int steps_ = m_.time.steps();
  Balance b0_;
  model::Summary sum_;
  double output_seconds_ = 0;  ///< series rows, frames and the observer's calls
};

}  // namespace

model::Summary simulate(const model::Model& m, model::Observer& observer, const CancelFlag* cancel,
                        const Checkpoints& checkpoints) {
  Run run(m, observer, checkpoints);
  run.begin();
  for (int n = run.first_step(); n <= run.steps(); ++n) {
    if (cancel && cancel->load()) return run.finish(false);
    run.advance(n);
  }
  return run.finish(true);
}

}  // namespace stoss
