#include "core/run/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>

#include "core/run/checkpoint_schedule.hpp"
#include "core/run/checks.hpp"
#include "core/run/measured_contact.hpp"
#include "core/run/measures.hpp"
#include "core/run/problem.hpp"
#include "core/run/recorder.hpp"
#include "core/run/series_table.hpp"
#include "core/run/solver_choice.hpp"
#include "core/run/static_scale.hpp"
#include "core/run/step_control.hpp"
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

std::string time_text(double t) {
  std::ostringstream out;
  out.precision(6);
  out << t;
  return out.str();
}

/// The message of a run whose step controller would need a step below time.min_step.
std::string below_min_step_message(int step, double t, double h, const std::string& reason,
                                   const ContactEvents& events, double min_step) {
  std::ostringstream out;
  out << "step " << step + 1 << " (t = " << time_text(t)
      << ") would need a step below time.min_step = " << time_text(min_step)
      << ": the try at h = " << time_text(h) << " was rejected (" << reason << ")";
  if (events.changed_nodes > 0 || events.offset > 0)
    out << "; forced by contact: " << (events.pair.empty() ? "a contact term" : events.pair) << ", "
        << events.changed_nodes << " nodes changed state";
  out << ". Hint: lower time.min_step, or raise time.tolerance.";
  return out.str();
}

/// The step a run with fixed steps takes from t towards `landing` (a frame time of output.interval or
/// the end): time.step, or the rest when it is within round-off of a step or shorter.
double fixed_step_to(double step, double t, double landing) {
  const double remaining = landing - t;
  return remaining <= step * (1 + 1e-6) ? remaining : step;
}

/// Each contact pair of `p` behind a MeasuredContact, which measures its force on the slave.
std::vector<std::unique_ptr<MeasuredContact>> measured_pairs(const Problem& p) {
  std::vector<std::unique_ptr<MeasuredContact>> out;
  for (const auto& pair : p.contact) out.push_back(std::make_unique<MeasuredContact>(*pair));
  return out;
}

/// The integrator's terms: the problem's, its contact pairs (the last ones) behind their measurements.
std::vector<time::Term*> terms_of(const Problem& p,
                                  const std::vector<std::unique_ptr<MeasuredContact>>& pairs) {
  std::vector<time::Term*> terms = p.terms();
  for (size_t k = 0; k < pairs.size(); ++k) terms[p.first_contact_term() + k] = pairs[k].get();
  return terms;
}

/// Per-item forces of one step from those of its converged substeps: Σ h_k f_k / Σ h_k, so that the
/// step's force times h is the substeps' impulse; exactly the substep's force when there is one.
class StepForces {
 public:
  void clear() { *this = StepForces(); }
  void add(double h, const std::vector<Eigen::Vector3d>& forces) {
    if (impulse_.empty()) impulse_.assign(forces.size(), Eigen::Vector3d::Zero());
    for (size_t k = 0; k < forces.size(); ++k) impulse_[k] += h * forces[k];
    last_ = forces;
    h_ += h;
    ++substeps_;
  }
  std::vector<Eigen::Vector3d> step_forces() const {
    if (substeps_ <= 1) return last_;
    std::vector<Eigen::Vector3d> out = impulse_;
    for (Eigen::Vector3d& f : out) f /= h_;
    return out;
  }

 private:
  std::vector<Eigen::Vector3d> impulse_, last_;
  double h_ = 0;
  int substeps_ = 0;
};

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
        measured_(measured_pairs(problem_)),
        terms_(terms_of(problem_, measured_)),
        integrator_(problem_.mass, terms_, problem_.fixed, time::make_scheme(m.time), newton_options(m),
                    problem_.length_scale, convergence_mass(m, problem_)),
        s_(initial_state(m, problem_)),
        store_(open_store(checkpoints)),
        recorder_(observer, store_ ? &*store_ : nullptr, problem_),
        series_(m),
        schedule_(m.output),
        end_(run_end(m)) {
    integrator_.set_velocity_map(problem_.velocity_map);
    integrator_.initialize(s_);
    if (m.time.adaptive()) controller_.emplace(m.time, integrator_.scheme(), initial_acceleration());
    if (store_ && checkpoints.resume && store_->exists()) resumed_ = load_checkpoint(*store_, m, terms_);
  }

  int first_step() const { return s_.step + 1; }
  /// Whether the run reached its end: after time.end / time.step steps, or with a tolerance or frames at
  /// output.interval (steps by time) at the end time.
  bool done() const { return by_time() ? s_.t >= end_ : s_.step >= steps_; }

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

  /// Solves step n (fixed: halving it when Newton fails; with a tolerance: until the controller accepts
  /// it), reports it, and keeps a checkpoint when one is due.
  /// @throws SolverError when the step cannot be solved, after observer.end.
  void advance(int n) {
    const auto t0 = Clock::now();
    const double landing = next_landing();
    const SolvedStep step = controller_ ? solve_adaptive(landing) : solve_fixed(landing);
    sum_.newton_iterations += step.newton.iterations;
    if (step.newton.substeps > 1) ++sum_.reduced_steps;
    const auto t_out = Clock::now();
    const Balance b = balance(problem_, s_);
    update_summary(sum_, b0_, b, step.contact);
    const std::vector<Eigen::Vector3d> reactions = reactions_.step_forces();
    const std::vector<Eigen::Vector3d> contact_forces = contact_forces_.step_forces();
    const std::vector<double> contact_areas = pair_areas();
    recorder_.step(series_.row(s_.step, s_.t,
                               {b, step.contact, &step.newton, seconds_since(t0), step.h, step.rejections,
                                &reactions, &contact_forces, &contact_areas}));
    const bool last = done();
    if (frame_due(n, last, s_.t == landing)) recorder_.frame(n, frame_of(s_, problem_));
    keep_checkpoint(n, last);
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
    add_verdict(m_, sum_, s_.x);
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
    if (controller_) controller_->restore(*c.controller);
    next_frame_ = static_cast<int>(c.frame_steps.size());
    observer_.resumed(s_.step);
    observer_.log("resumed from step " + std::to_string(s_.step) + " (t = " + std::to_string(s_.t) +
                  ") of the checkpoint " + store_->state_file().string() + ": computing steps " +
                  std::to_string(s_.step + 1) +
                  (by_time() ? " to t = " + time_text(end_) : " to " + std::to_string(steps_)));
  }

  /// A step: its Newton solves, contact row, h and the controller's rejections before it.
  struct SolvedStep {
    time::ReducedStep newton;
    ContactRow contact;
    double h = 0;
    int rejections = 0;
  };

  bool by_time() const { return controller_ || m_.output.interval; }

  /// a(0) of a run that starts stress-free: gravity on every free dof (problem.cpp), else 0.
  Eigen::VectorXd initial_acceleration() const {
    Eigen::VectorXd a = Eigen::VectorXd::Zero(s_.x.size());
    if (!m_.gravity) return a;
    for (Eigen::Index i = 0; i < a.size(); ++i)
      if (!problem_.fixed[static_cast<size_t>(i)]) a[i] = (*m_.gravity)[i % 3];
    return a;
  }

  /// Where a run steps by time ends: time.end, or the last frame time of output.interval when time.end is
  /// that within round-off (so that frames/time[k] = k·interval holds for the last frame too).
  static double run_end(const model::Model& m) {
    if (!m.output.interval) return m.time.end;
    const double frames = std::round(m.time.end / *m.output.interval);
    const double last = frames * *m.output.interval;
    return std::abs(last - m.time.end) <= 1e-9 * *m.output.interval ? last : m.time.end;
  }

  /// The next time the run must land on: the next frame time k·interval before the end, or the end.
  double next_landing() const {
    if (!m_.output.interval) return end_;
    const double frame_time = static_cast<double>(next_frame_) * *m_.output.interval;
    return frame_time < end_ ? frame_time : end_;
  }

  bool frame_due(int n, bool last, bool landed) {
    if (!m_.output.interval) return m_.output.frame_due(n, last ? n : steps_after(n));
    if (landed || last) ++next_frame_;
    return landed || last;
  }
  /// A step count beyond n: frame_due's "the last step" is then not n.
  static int steps_after(int n) { return n == std::numeric_limits<int>::max() ? n : n + 1; }

  /// Today's fixed step: time.step (or the rest to the landing time), halved when Newton fails.
  SolvedStep solve_fixed(double landing) {
    SolvedStep out;
    out.h =
        by_time() ? fixed_step_to(m_.time.step, s_.t, landing) : std::min(m_.time.step, m_.time.end - s_.t);
    const int step0 = s_.step;
    const double time0 = s_.t;
    const auto log = [&](const std::string& line) { observer_.log(line); };
    clear_step_forces();
    out.newton = time::step_with_reduction(integrator_, s_, out.h, max_step_halvings, log, [&] {
      add_substep(out.contact, contact_row(problem_, &integrator_));
      add_step_forces();
    });
    if (!out.newton.converged) fail(failure_message(step0, time0, out.h, out.newton));
    if (by_time() && out.h == landing - time0) s_.t = landing;  // exactly on the frame time
    return out;
  }

  /// A step chosen by the controller (docs/theory.md §2.7): tries until one is accepted; a rejected try is
  /// undone (state and term histories) and logged with its reason.
  SolvedStep solve_adaptive(double landing) {
    SolvedStep out;
    const time::State before = s_;
    std::vector<time::TermState> histories;
    for (const time::Term* t : terms_) histories.push_back(t->save_state());
    const auto log = [&](const std::string& line) { observer_.log(line); };
    for (;;) {
      const double h = controller_->step_to(before.t, landing);
      const solve::NewtonResult r = integrator_.step(s_, h, log);
      out.newton.iterations += r.iterations;
      out.newton.residuals = r.residuals;
      ContactEvents events;
      std::string reason;
      if (r.converged) {
        events = contact_events();
        const double taken = integrator_.advanced();  // < h when the step ended at a located event (§4.6.2)
        const StepVerdict verdict = controller_->judge(taken, before, s_, events);
        if (verdict.accepted) return accepted(out, before, taken, landing);
        reason = verdict.reason;
        undo_step(before, histories);
      } else {
        controller_->newton_failed(h);
        reason = "newton: " + r.failure;
      }
      ++out.rejections;
      observer_.log("rejected step at t = " + time_text(before.t) + ", h = " + time_text(h) + ": " + reason);
      if (!controller_->can_retry(h))
        fail(below_min_step_message(before.step, before.t, h, reason, events, m_.time.min_step));
    }
  }

  SolvedStep& accepted(SolvedStep& out, const time::State& before, double h, double landing) {
    s_.t = h == landing - before.t ? landing : before.t + h;
    s_.step = before.step + 1;
    out.newton.converged = true;
    out.newton.substeps = 1;
    out.contact = contact_row(problem_, &integrator_);
    out.h = h;
    clear_step_forces();
    add_step_forces();
    return out;
  }

  void clear_step_forces() {
    reactions_.clear();
    contact_forces_.clear();
  }
  /// After a converged integrator step: its supports' and pairs' forces, weighted by the h it advanced.
  void add_step_forces() {
    const double h = integrator_.advanced();
    reactions_.add(h, problem_.entry_reactions(integrator_.reaction()));
    std::vector<Eigen::Vector3d> forces;
    for (const auto& pair : measured_) forces.push_back(pair->slave_force());
    contact_forces_.add(h, forces);
  }
  /// Each pair's contact area at the step's end (ContactReport::contact_area).
  std::vector<double> pair_areas() const {
    std::vector<double> areas;
    for (const auto& pair : problem_.contact) areas.push_back(pair->report().contact_area);
    return areas;
  }

  /// Back to the state before a rejected try, as a run resumed there would be (restore_state).
  void undo_step(const time::State& before, const std::vector<time::TermState>& histories) {
    s_ = before;
    for (size_t k = 0; k < terms_.size(); ++k) terms_[k]->restore_state(histories[k], s_.x, s_.v);
    integrator_.forget_factorization();
  }

  /// The contact events of the last converged try: the largest event_offset, and the pair whose nodes
  /// changed state most.
  ContactEvents contact_events() const {
    ContactEvents events;
    for (const time::Term* t : terms_) events.offset = std::max(events.offset, t->event_offset());
    for (const auto& pair : problem_.contact) {
      const contact::ContactReport& r = pair->report();
      const int changed = r.activations + r.releases + r.switches;
      if (changed > events.changed_nodes) {
        events.changed_nodes = changed;
        events.pair = pair->name();
      }
    }
    return events;
  }

  /// Logs `message`, ends the run as failed (its partial result stays) and throws SolverError.
  [[noreturn]] void fail(const std::string& message) {
    observer_.log(message);
    finish(false);
    throw SolverError(message);
  }

  void keep_checkpoint(int n, bool last) {
    const int steps = last ? n : steps_after(n);
    if (!store_ || !schedule_.may_land(n, steps)) return;
    if (schedule_.due(n, steps)) {
      store_->write(
          checkpoint_of(m_, s_, terms_, sum_, recorder_, controller_ ? &controller_->state() : nullptr));
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
  std::vector<std::unique_ptr<MeasuredContact>> measured_;  ///< the contact pairs as the integrator sees them
  std::vector<time::Term*> terms_;
  time::Integrator integrator_;
  time::State s_;
  std::optional<CheckpointStore> store_;
  std::optional<Checkpoint> resumed_;
  Recorder recorder_;
  const SeriesRows series_;
  CheckpointSchedule schedule_;
  const int steps_ = m_.time.steps();
  const double end_;                          ///< where a run stepping by time ends (run_end)
  std::optional<StepController> controller_;  ///< with time.tolerance
  int next_frame_ = 1;                        ///< with output.interval: k of the next frame time
  Balance b0_;
  model::Summary sum_;
  StepForces reactions_, contact_forces_;  ///< of the step being solved: series reaction_force, contact_force
  double output_seconds_ = 0;              ///< series rows, frames and the observer's calls
};

}  // namespace

model::Summary simulate(const model::Model& m, model::Observer& observer, const CancelFlag* cancel,
                        const Checkpoints& checkpoints) {
  Run run(m, observer, checkpoints);
  run.begin();
  for (int n = run.first_step(); !run.done(); ++n) {
    if (cancel && cancel->load()) return run.finish(false);
    run.advance(n);
  }
  return run.finish(true);
}

}  // namespace stoss
