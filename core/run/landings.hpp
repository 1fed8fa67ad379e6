#pragma once
/// @file Where a run's steps must land and when it writes a frame: every output.every-th step, or with
/// output.interval at each frame time k·interval exactly and at the end (docs/results.md, "Frames").

#include <limits>

#include "core/model/model.hpp"

namespace stoss::run {

/// The step a run with fixed steps takes from t towards `landing` (a frame time of output.interval or
/// the end): time.step, or the rest when it is within round-off of a step or shorter.
double fixed_step_to(double step, double t, double landing);

/// A step count beyond n: a frame or checkpoint schedule's "the last step" is then not n.
inline int steps_after(int n) {
  return n == std::numeric_limits<int>::max() ? n : n + 1;
}

class Landings {
 public:
  explicit Landings(const model::Model& m);
  /// Where a run stepping by time ends: time.end, or the last frame time of output.interval when
  /// time.end is that within round-off (so that frames/time[k] = k·interval holds for the last frame too).
  double end() const { return end_; }
  /// The next time the run must land on: the next frame time k·interval before the end, or the end.
  double next() const;
  /// Whether step n writes a frame (`last`: it ends the run; `landed`: it ended on next()); moves on to
  /// the next frame time when it does.
  bool frame_due(int n, bool last, bool landed);
  /// k of the next frame time (a checkpoint keeps it through its frame count).
  void set_next_frame(int k) { next_frame_ = k; }

 private:
  const model::OutputSpec& output_;
  const double end_;
  int next_frame_ = 1;
};

}  // namespace stoss::run
