#include "core/run/landings.hpp"

#include <cmath>

namespace stoss::run {
namespace {

double run_end(const model::Model& m) {
  if (!m.output.interval) return m.time.end;
  const double frames = std::round(m.time.end / *m.output.interval);
  const double last = frames * *m.output.interval;
  return std::abs(last - m.time.end) <= 1e-9 * *m.output.interval ? last : m.time.end;
}

}  // namespace

double fixed_step_to(double step, double t, double landing) {
  const double remaining = landing - t;
  return remaining <= step * (1 + 1e-6) ? remaining : step;
}

Landings::Landings(const model::Model& m) : output_(m.output), end_(run_end(m)) {}

double Landings::next() const {
  if (!output_.interval) return end_;
  const double frame_time = static_cast<double>(next_frame_) * *output_.interval;
  return frame_time < end_ ? frame_time : end_;
}

bool Landings::frame_due(int n, bool last, bool landed) {
  if (!output_.interval) return output_.frame_due(n, last ? n : steps_after(n));
  if (landed || last) ++next_frame_;
  return landed || last;
}

}  // namespace stoss::run
