#include "server/cli/progress.hpp"

namespace stoss::cli {

void ProgressObserver::begin(const model::Model& model, const model::SeriesLayout&) {
  start_ = last_print_ = Clock::now();
  steps_ = model.time.steps();
  end_time_ = model.time.end;
}

void ProgressObserver::step(const model::StepRow& row) {
  const auto now = Clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (row.step <= first_step_ || elapsed < 1.0 || std::chrono::duration<double>(now - last_print_).count() < 0.5)
    return;
  last_print_ = now;
  const double eta = elapsed / (row.step - first_step_) * (steps_ - row.step);
  std::fprintf(out_, "\rstep %d/%d  t = %.6g/%.6g  elapsed %.1f s  ETA %.1f s   ", row.step, steps_, row.time,
               end_time_, elapsed, eta);
  std::fflush(out_);
  printed_ = true;
}

void ProgressObserver::resumed(int step) {
  start_ = Clock::now();
  first_step_ = step;
}

void ProgressObserver::log(const std::string& line) {
  std::fprintf(out_, "%s%s\n", printed_ ? "\n" : "", line.c_str());
  printed_ = false;
}

void ProgressObserver::end(const model::Summary&) {
  if (printed_) std::fprintf(out_, "\n");
}

}  // namespace stoss::cli
