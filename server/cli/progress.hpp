#pragma once
/// @file Progress of a command-line run on stderr: step, simulated time, ETA, for runs over a second.

#include <chrono>
#include <cstdio>

#include "core/model/observer.hpp"

namespace stoss::cli {

/// Prints "step n/N  t = …  ETA …" at most twice a second, starting once the run has taken a second.
class ProgressObserver : public model::Observer {
 public:
  explicit ProgressObserver(std::FILE* out = stderr) : out_(out) {}
  void begin(const model::Model& model, const model::SeriesLayout&) override;
  void step(const model::StepRow& row) override;
  void log(const std::string& line) override;
  void resumed(int step) override;
  void end(const model::Summary& summary) override;

 private:
  using Clock = std::chrono::steady_clock;
  std::FILE* out_;
  Clock::time_point start_, last_print_;
  int steps_ = 0;
  int first_step_ = 0;  ///< the step the rate counts from: 0, or the checkpoint's
  double end_time_ = 0;
  bool printed_ = false;
};

}  // namespace stoss::cli
