#include "core/time/step_reduction.hpp"

#include <cstdio>

namespace stoss::time {
namespace {

struct Reducer {
  Integrator& integrator;
  State& s;
  int max_halvings;
  const LogFunction& log;
  const std::function<void()>& after_substep;
  int step0;  ///< the step's number before it started
  ReducedStep out;

  /// Solves t → t + h at reduction depth `depth` (h = full step / 2^depth); an integrator step that ends at
  /// a located contact event (§4.6.2) is followed by the rest of h.
  bool solve(double h, int depth) {
    for (double left = h; left > 1e-10 * h;) {
      double covered = 0;
      if (!solve_once(left, depth, covered)) return false;
      left -= covered;
    }
    return true;
  }

  /// One integrator step of at most h, or its halves when it fails; `covered` gets the time advanced.
  bool solve_once(double h, int depth, double& covered) {
    const solve::NewtonResult r = integrator.step(s, h, log);
    out.iterations += r.iterations;
    out.residuals = r.residuals;
    if (r.converged) {
      covered = integrator.advanced();
      if (covered < h)
        ++out.event_substeps;  // ended at a located contact event (§4.6.2)
      else
        ++out.substeps;
      if (after_substep) after_substep();
      return true;
    }
    covered = h;
    if (depth == 0) out.failure = r.failure;
    if (depth == max_halvings) {
      if (depth > 0)
        out.failure += "; with automatic step reduction it still failed at t = " + time_text(s.t) +
                       " in a substep of h/" + std::to_string(1 << depth) + ": " + r.failure;
      return false;
    }
    if (log) log(reduction_line(h, depth, r));
    return solve(h / 2, depth + 1) && solve(h / 2, depth + 1);
  }

  static std::string time_text(double t) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", t);
    return text;
  }

  std::string reduction_line(double h, int depth, const solve::NewtonResult& r) const {
    return "step " + std::to_string(step0 + 1) + " (t = " + time_text(s.t) + ", h = " + time_text(h) +
           ") did not converge (" + r.failure + "); automatic step reduction: retrying as 2 substeps of h/" +
           std::to_string(2 << depth);
  }
};

}  // namespace

ReducedStep step_with_reduction(Integrator& integrator, State& s, double h, int max_halvings,
                                const LogFunction& log, const std::function<void()>& after_substep) {
  const double t0 = s.t;
  const int step0 = s.step;
  Reducer reducer{integrator, s, max_halvings, log, after_substep, step0, {}};
  reducer.out.converged = reducer.solve(h, 0);
  if (reducer.out.converged) {
    s.t = t0 + h;  // the substeps' sum, without their round-off
    s.step = step0 + 1;
  }
  return reducer.out;
}

}  // namespace stoss::time
