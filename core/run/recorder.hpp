#pragma once
/// @file What a run reports, remembered for its checkpoints.

#include <vector>

#include "core/model/observer.hpp"
#include "core/run/checkpoint.hpp"
#include "core/run/problem.hpp"

namespace stoss::run {

/// Series rows and frames go to the observer and, when the run keeps checkpoints, into the checkpoint
/// (rows) and its directory (frames).
class Recorder {
 public:
  /// `store`: null when the run keeps no checkpoints. `problem` gives the stresses of replayed frames.
  Recorder(model::Observer& observer, CheckpointStore* store, const Problem& problem)
      : observer_(observer), store_(store), problem_(problem) {}
  void step(const model::StepRow& row);
  void frame(int step, const model::Frame& frame);
  /// Gives the observer the rows and frames up to the checkpoint again, in the order the run gave them.
  void replay(const Checkpoint& c);
  const std::vector<model::StepRow>& rows() const { return rows_; }
  const std::vector<int>& frame_steps() const { return frame_steps_; }

 private:
  model::Observer& observer_;
  CheckpointStore* store_;
  const Problem& problem_;
  std::vector<model::StepRow> rows_;
  std::vector<int> frame_steps_;
};

}  // namespace stoss::run
