#include "core/run/step_messages.hpp"

#include <sstream>

#include "core/solve/newton.hpp"

namespace stoss::run {

std::string time_text(double t) {
  std::ostringstream out;
  out.precision(6);
  out << t;
  return out.str();
}

std::string failure_message(int step, double t, double h, const time::ReducedStep& r) {
  std::ostringstream out;
  out << "step " << step + 1 << " (t = " << t << " → " << t + h << ") did not converge: " << r.failure
      << "; residual history: " << solve::format_history(r.residuals)
      << ". Hint: reduce time.step, or check the material and initial velocities.";
  return out.str();
}

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

}  // namespace stoss::run
