#include "core/run/step_control.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/run/problem.hpp"
#include "core/time/generalized_alpha.hpp"

namespace stoss::run {
namespace {

/// Of the step proposal (2.19): safety factor and the bounds of one change.
constexpr double safety = 0.8, least_factor = 0.2, most_factor = 2;
/// Shares of time.tolerance (2.18): of one step's truncation estimate, and of the frozen gap a new contact
/// keeps (Term::event_offset: the largest nodal error it leaves, not summed over the nodes).
constexpr double step_share = 0.05, offset_share = 0.5;

std::string short_number(double x) {
  std::ostringstream out;
  out.precision(3);
  out << x;
  return out.str();
}

}  // namespace

double largest_nodal_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  double largest = 0;
  for (Eigen::Index i = 0; i + 2 < a.size(); i += 3)
    largest = std::max(largest, (a.segment<3>(i) - b.segment<3>(i)).norm());
  return largest;
}

StepController::StepController(const model::TimeSpec& time, const time::Scheme& scheme,
                               Eigen::VectorXd initial_acceleration)
    : time_(time), initial_acceleration_(std::move(initial_acceleration)) {
  const auto* newmark = dynamic_cast<const time::GeneralizedAlpha*>(&scheme);
  midpoint_type_ = newmark == nullptr;
  if (newmark) beta_ = newmark->beta();
  state_.next_step = time.step;
  // Newmark's a_0 is the initial acceleration (2.10); the midpoint schemes' s.a is 0 before their first
  // step, where a(0) stands in for ā_{−½} at h_{−1} = 0.
  state_.has_history = !midpoint_type_ || initial_acceleration_.size() > 0;
}

double StepController::step_to(double t, double landing) const {
  const double remaining = landing - t, proposal = state_.next_step;
  if (remaining <= proposal * (1 + 1e-9)) return remaining;
  if (remaining < 2 * proposal) return remaining / 2;  // two like steps rather than a sliver
  return proposal;
}

double StepController::truncation_estimate(double h, const time::State& before,
                                           const time::State& after) const {
  const bool first =
      midpoint_type_ && state_.previous_step == 0 && initial_acceleration_.size() == after.a.size();
  const double jump = largest_nodal_distance(after.a, first ? initial_acceleration_ : before.a);
  if (midpoint_type_) return h * h * h / 12 * jump / ((h + state_.previous_step) / 2);  // (2.16)
  return std::abs(beta_ - 1.0 / 6) * h * h * jump;                                      // (2.17)
}

StepVerdict StepController::judge(double h, const time::State& before, const time::State& after,
                                  const ContactEvents& events) {
  const bool event = events.changed_nodes > 0 || events.offset > 0;
  // At a contact event the acceleration jump is the impact's impulse, no truncation error; what the
  // event leaves is the frozen gap (2.18).
  const bool estimate = state_.has_history && !event;
  StepVerdict v;
  v.error = estimate ? truncation_estimate(h, before, after) : events.offset * step_share / offset_share;
  v.target = step_share * *time_.tolerance;
  v.accepted = v.error <= v.target;
  // error / target goes like h³ in smooth motion, like h at a contact event (gap ≤ h |ġ|)
  const double order = event ? 1 : 3;
  // (2.19); a step at or right after a contact event, which (2.16) does not see, does not grow
  const double most = event || !state_.has_history ? 1.0 : most_factor;
  const double factor =
      v.error > 0 ? std::clamp(safety * std::pow(v.target / v.error, 1 / order), least_factor, most) : most;
  if (!v.accepted) {
    state_.next_step = std::min(h * factor, std::min(state_.next_step, h) * 0.9);
    v.reason = (event ? "contact: " + (events.pair.empty() ? std::string("a contact term") : events.pair) +
                            ", " + std::to_string(events.changed_nodes) + " nodes changed state, "
                      : std::string("error: ")) +
               "estimate " + short_number(v.error) + " > " + short_number(v.target) +
               (events.offset > 0 ? " (frozen gap " + short_number(events.offset) + ")" : std::string());
    return v;
  }
  const bool clipped = h < state_.next_step;  // landed on a frame time or the end: keep the proposal
  double next = h * factor;
  if (clipped && factor >= 1) next = std::max(next, state_.next_step);
  state_.next_step = std::clamp(next, time_.min_step, time_.max_step);
  state_.previous_step = h;
  state_.has_history = !event;  // an event's acceleration jump is no truncation error of the next step
  return v;
}

bool StepController::can_retry(double rejected_h) {
  if (state_.next_step >= time_.min_step) return true;
  if (rejected_h <= time_.min_step) return false;
  state_.next_step = time_.min_step;
  return true;
}

ContactEvents contact_events(const std::vector<time::Term*>& terms, const Problem& problem) {
  ContactEvents events;
  for (const time::Term* t : terms) events.offset = std::max(events.offset, t->event_offset());
  for (const auto& pair : problem.contact) {
    const contact::ContactReport& r = pair->report();
    const int changed = r.activations + r.releases + r.switches;
    if (changed > events.changed_nodes) {
      events.changed_nodes = changed;
      events.pair = pair->name();
    }
  }
  return events;
}

}  // namespace stoss::run
