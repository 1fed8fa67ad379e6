#pragma once
/// @file Steps chosen by a tolerance (time.tolerance, docs/theory.md §2.7): a local error estimate of each
/// converged step decides whether it is accepted and how large the next one is.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/model/model.hpp"
#include "core/time/scheme.hpp"
#include "core/time/term.hpp"

namespace stoss::run {

struct Problem;

/// What the controller carries from one accepted step to the next: the part of a checkpoint a run with a
/// tolerance adds (core/run/checkpoint.hpp).
struct StepControllerState {
  double next_step = 0;      ///< the step the controller proposes next (before a clip to a frame time)
  double previous_step = 0;  ///< h of the last accepted step; 0 before the first
  /// Whether s.a before the next step is the previous step's (2.16)/(2.17) acceleration (at the start: the
  /// initial acceleration), so that the estimate has its two accelerations: not after a contact event.
  bool has_history = false;
};

/// How a converged step went at contact: the largest event_offset of the terms (time::Term) and the
/// pair whose nodes changed state most (activations, releases, face switches).
struct ContactEvents {
  double offset = 0;
  int changed_nodes = 0;
  std::string pair;  ///< the term name of that pair; empty without changes
};

/// The contact events of the last converged try of `terms` (the run's, its pairs among them): the largest
/// event_offset, and the pair of `problem` whose nodes changed state most.
ContactEvents contact_events(const std::vector<time::Term*>& terms, const Problem& problem);

/// The controller's judgement of one step.
struct StepVerdict {
  bool accepted = false;
  double error = 0, target = 0;  ///< the estimate and what it was held to (length)
  std::string reason;            ///< of a rejection: "error …" or "contact …"
};

/// The controller of docs/theory.md §2.7 for one run: the estimates (2.16)/(2.17), the budgets (2.18) and
/// the step update (2.19), clamped to [min_step, max_step].
class StepController {
 public:
  /// `initial_acceleration`: a(0) per dof, for (2.16) at the first step of the midpoint-type schemes
  /// (a run starts stress-free: gravity on the free dofs, else 0).
  StepController(const model::TimeSpec& time, const time::Scheme& scheme,
                 Eigen::VectorXd initial_acceleration = {});

  const StepControllerState& state() const { return state_; }
  void restore(const StepControllerState& state) { state_ = state; }
  /// The step to try next from t, given the next time the run must land on (a frame time or the end):
  /// the proposal, or the distance when it is within the proposal, or half of it when within two.
  double step_to(double t, double landing) const;

  /// Judges the converged step of size h from the state `before` to `after` (their accelerations a).
  /// Accepting or rejecting also sets the next proposal.
  StepVerdict judge(double h, const time::State& before, const time::State& after,
                    const ContactEvents& events);
  /// A Newton failure at h: the next proposal is h/4.
  void newton_failed(double h) { state_.next_step = h / 4; }
  /// Whether the proposal after a rejection is still at least min_step; the last try is at min_step itself.
  bool can_retry(double rejected_h);

 private:
  double truncation_estimate(double h, const time::State& before, const time::State& after) const;

  model::TimeSpec time_;
  bool midpoint_type_;  ///< energy-momentum and midpoint: (2.16); else Newmark's (2.17) with beta_
  double beta_ = 0;
  Eigen::VectorXd initial_acceleration_;  ///< a(0), in place of ā_{−½} at the first step (2.16)
  StepControllerState state_;
};

/// Largest nodal norm of a − b (3 per node).
double largest_nodal_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b);

}  // namespace stoss::run
