#include "server/cli/progress.hpp"

#include <algorithm>
#include <cmath>

namespace stoss::cli {

void ProgressObserver::begin(const model::Model& model, const model::SeriesLayout&) {
  start_ = last_print_ = Clock::now();
  steps_ = model.time.steps();
  end_time_ = model.time.end;
  adaptive_ = model.time.adaptive();
}

void ProgressObserver::step(const model::StepRow& row) {
  last_time_ = row.time;
  const auto now = Clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (row.step <= first_step_ || elapsed < 1.0 ||
      std::chrono::duration<double>(now - last_print_).count() < 0.5)
    return;
  last_print_ = now;
  std::fprintf(out_, "\r%s   ", line(row, elapsed).c_str());
  std::fflush(out_);
  printed_ = true;
}

std::string ProgressObserver::line(const model::StepRow& row, double elapsed) const {
  char text[200];
  if (!adaptive_) {
    const double eta = elapsed / (row.step - first_step_) * (steps_ - row.step);
    std::snprintf(text, sizeof text, "step %d/%d  t = %.6g/%.6g  elapsed %.1f s  ETA %.1f s", row.step,
                  steps_, row.time, end_time_, elapsed, eta);
    return text;
  }
  const double done = row.time - first_time_;
  const double eta = done > 0 ? elapsed / done * std::max(0.0, end_time_ - row.time) : 0;
  std::snprintf(text, sizeof text, "step %d  t = %.6g/%.6g (%.0f %%)  elapsed %.1f s  ETA %.1f s", row.step,
                row.time, end_time_, std::floor(100 * row.time / end_time_), elapsed, eta);
  return text;
}

void ProgressObserver::resumed(int step) {
  start_ = Clock::now();
  first_step_ = step;
  first_time_ = last_time_;
}

void ProgressObserver::log(const std::string& line) {
  std::fprintf(out_, "%s%s\n", printed_ ? "\n" : "", line.c_str());
  printed_ = false;
}

void ProgressObserver::end(const model::Summary&) {
  if (printed_) std::fprintf(out_, "\n");
}

}  // namespace stoss::cli
