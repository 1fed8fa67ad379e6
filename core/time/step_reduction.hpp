#pragma once
/// @file Automatic step reduction: a step whose Newton solve fails is retried in substeps (issue 6,
/// item 4; docs/theory.md §2.1 — every scheme's step equations hold for any h).

#include <functional>

#include "core/time/integrator.hpp"

namespace stoss::time {

/// What the (sub)steps of one step of size h added up to.
struct ReducedStep {
  bool converged = false;
  int substeps = 0;  ///< converged integrator steps that make up the step: 1 without reduction
  /// Converged integrator steps that ended early, at a located contact event (docs/theory.md §4.6.2); each is
  /// followed by the rest of its (sub)step, which substeps counts.
  int event_substeps = 0;
  int iterations = 0;             ///< Newton iterations over every solve tried, failed ones included
  std::vector<double> residuals;  ///< the last solve's residual history (converged or failed)
  std::string failure;            ///< why it stopped, when not converged
};

/// Solves t → t + h with `integrator`. A (sub)step that does not converge is retried as two halves,
/// recursively, down to h / 2^max_halvings (so a hard moment costs 2, 3, 4, … substeps, not 2^k
/// everywhere); a line goes to `log` each time it acts. `after_substep` runs after every converged
/// integrator step (collect per-substep reports there: terms reset theirs in prepare_step).
/// On success s is at t + h with s.step advanced by exactly one; on failure s is at the last converged
/// substep and `failure` names the full step's reason and the smallest substep's.
/// @note Contact terms see prepare_step/end_step per substep: the face assignment, active set and
///       multiplier history are committed at each converged substep.
ReducedStep step_with_reduction(Integrator& integrator, State& s, double h, int max_halvings,
                                const LogFunction& log, const std::function<void()>& after_substep = {});

}  // namespace stoss::time
