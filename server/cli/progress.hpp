#pragma once
/// @file Progress of a command-line run on stderr: step, simulated time, ETA, for runs over a second.

#include <chrono>
#include <cstdio>
#include <string>

#include "core/model/observer.hpp"

namespace stoss::cli {

/// Prints "step n/N  t = …  ETA …" at most twice a second, starting once the run has taken a second. With
/// time.tolerance the steps to go are unknown: "step n  t = …/… (p %)  ETA …", p = time/end and the ETA from
/// the wall time per unit of simulated time.
class ProgressObserver : public model::Observer {
 public:
  explicit ProgressObserver(std::FILE* out = stderr) : out_(out) {}
  void begin(const model::Model& model, const model::SeriesLayout&) override;
  void step(const model::StepRow& row) override;
  void log(const std::string& line) override;
  void resumed(int step) override;
  void end(const model::Summary& summary) override;

  /// The line for `row` after `elapsed` wall seconds (no leading carriage return).
  std::string line(const model::StepRow& row, double elapsed) const;

 private:
  using Clock = std::chrono::steady_clock;
  std::FILE* out_;
  Clock::time_point start_, last_print_;
  int steps_ = 0;
  int first_step_ = 0;  ///< the step the rate counts from: 0, or the checkpoint's
  double end_time_ = 0;
  double first_time_ = 0;  ///< the simulated time at first_step_
  double last_time_ = 0;   ///< of the last row (at resumed(): the checkpoint's)
  bool adaptive_ = false;
  bool printed_ = false;
};

}  // namespace stoss::cli
