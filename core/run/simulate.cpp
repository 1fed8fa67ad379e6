#include "core/run/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include "core/parallel/element_share.hpp"
#include "core/run/checkpoint_schedule.hpp"
#include "core/run/checks.hpp"
#include "core/run/landings.hpp"
#include "core/run/measured_contact.hpp"
#include "core/run/measures.hpp"
#include "core/run/problem.hpp"
#include "core/run/recorder.hpp"
#include "core/run/series_table.hpp"
#include "core/run/solver_choice.hpp"
#include "core/run/static_scale.hpp"
#include "core/run/step_control.hpp"
#include "core/run/step_forces.hpp"
#include "core/run/step_messages.hpp"
#include "core/run/timing.hpp"
#include "core/time/integrator.hpp"
#include "core/time/step_reduction.hpp"

namespace stoss {
namespace {

using namespace run;

/// Most halvings of a step whose Newton solve fails (time/step_reduction.hpp): substeps down to h/16.
constexpr int max_step_halvings = 4;

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
        landings_(m) {
    integrator_.set_velocity_map(problem_.velocity_map);
    if (const parallel::ElementShare& share = parallel::element_share(); share.shared())
      integrator_.keep_inertia_rows(share.own_rows());
    integrator_.initialize(s_);
    if (m.time.adaptive()) controller_.emplace(m.time, integrator_.scheme(), initial_acceleration());
    if (store_ && checkpoints.resume && store_->exists()) resumed_ = load_checkpoint(*store_, m, terms_);
  }

  int first_step() const { return s_.step + 1; }
  /// Whether the run reached its end: after time.end / time.step steps, or with a tolerance or frames at
  /// output.interval (steps by time) at the end time.
  bool done() const { return by_time() ? s_.t >= landings_.end() : s_.step >= steps_; }

  /// Tells the observer of the run, then gives it step 0, or the rows and frames up to the checkpoint.
  void begin() {
    const auto t_out = Clock::now();
    observer_.begin(m_, series_.layout());
    if (m_.solver.linear != model::LinearSolver::direct) observer_.log(linear_solver_line(m_));
    b0_ = balance(problem_, s_);  // the initial state, also when resuming: the drifts are against it
    before_ = b0_;
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
    const double landing = landings_.next();
    const SolvedStep step = controller_ ? solve_adaptive(landing) : solve_fixed(landing);
    sum_.newton_iterations += step.newton.iterations;
    if (step.newton.substeps > 1) ++sum_.reduced_steps;
    const auto t_out = Clock::now();
    const Balance b = balance(problem_, s_);
    update_summary(sum_, b0_, b, step.contact);
    const std::vector<Eigen::Vector3d> reactions = reported_forces(reactions_);
    update_impulse_balance(sum_, before_, b, step_impulse(step.h, reactions));
    before_ = b;
    const std::vector<Eigen::Vector3d> contact_forces = reported_forces(contact_forces_);
    const std::vector<double> contact_areas = pair_areas();
    recorder_.step(series_.row(s_.step, s_.t,
                               {b, step.contact, &step.newton, seconds_since(t0), step.h, step.rejections,
                                &reactions, &contact_forces, &contact_areas}));
    const bool last = done();
    if (landings_.frame_due(n, last, s_.t == landing)) recorder_.frame(n, frame_of(s_, problem_));
    keep_checkpoint(n, last);
    output_seconds_ += seconds_since(t_out);
  }

  /// The summary, told to the observer (observer.end).
  model::Summary finish(bool completed) {
    sum_.completed = completed;
    sum_.steps = s_.step;
    sum_.end_time = s_.t;
    sum_.newton_iterations_per_step = s_.step > 0 ? double(sum_.newton_iterations) / s_.step : 0.0;
    add_timing(sum_, integrator_, problem_, seconds_since(wall0_), output_seconds_);
    report_linear_solver(integrator_.linear_solver(), sum_, observer_);
    add_verdict(m_, sum_, s_.x);
    observer_.end(sum_);
    return sum_;
  }

 private:
  void resume(const Checkpoint& c) {
    recorder_.replay(c);
    s_ = c.state;
    for (size_t k = 0; k < terms_.size(); ++k) terms_[k]->restore_state(c.terms[k].second, s_.x, s_.v);
    before_ = balance(problem_, s_);
    load_impulse_ = problem_.load_impulse();
    sum_ = c.summary;
    sum_.resumed_from_step = s_.step;
    if (controller_) controller_->restore(*c.controller);
    landings_.set_next_frame(static_cast<int>(c.frame_steps.size()));
    observer_.resumed(s_.step);
    observer_.log("resumed from step " + std::to_string(s_.step) + " (t = " + std::to_string(s_.t) +
                  ") of the checkpoint " + store_->state_file().string() + ": computing steps " +
                  std::to_string(s_.step + 1) +
                  (by_time() ? " to t = " + time_text(landings_.end()) : " to " + std::to_string(steps_)));
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
        events = contact_events(terms_, problem_);
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

  /// A step's series row of forces: the substeps' impulse over h, or a static step's end equilibrium (§5b.9).
  std::vector<Eigen::Vector3d> reported_forces(const StepForces& forces) const {
    return m_.time.scheme == model::Scheme::equilibrium ? forces.end_forces() : forces.step_forces();
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
  /// The step's external impulse (StepImpulse) from its h and its supports' reactions.
  StepImpulse step_impulse(double h, const std::vector<Eigen::Vector3d>& reactions) {
    StepImpulse j;
    const Eigen::Vector3d loads = problem_.load_impulse();
    j.loads = loads - load_impulse_;
    load_impulse_ = loads;
    j.gravity = h * problem_.gravity_force();
    for (const Eigen::Vector3d& r : reactions) j.supports += h * r;
    return j;
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
    integrator_.refresh_factorization();  // the next step as a run resumed from here computes it
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
  Landings landings_;                         ///< where steps land, when frames are due
  std::optional<StepController> controller_;  ///< with time.tolerance
  Balance b0_;
  Balance before_;                                          ///< of the last step: the impulse balance's start
  Eigen::Vector3d load_impulse_ = Eigen::Vector3d::Zero();  ///< the loads' impulse at its end
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
    if (parallel::on_any_rank(cancel && cancel->load())) return run.finish(false);
    run.advance(n);
  }
  return run.finish(true);
}

}  // namespace stoss
