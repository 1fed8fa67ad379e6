#pragma once
/// @file When a run writes a checkpoint, what goes into it, and whether one may be resumed.

#include <vector>

#include "core/model/model.hpp"
#include "core/run/checkpoint.hpp"
#include "core/run/recorder.hpp"
#include "core/run/timing.hpp"
#include "core/time/term.hpp"

namespace stoss::run {

/// When a run writes a checkpoint: after every checkpoint_every-th step, or once checkpoint_seconds of wall
/// time passed since the last; never after the last step (the result has it all). A checkpoint makes the
/// next step refactorise, so where checkpoints may land must not depend on wall time, or a run would
/// compute other round-off when slower (beside another job): by wall time they land only on every
/// wall_time_stride-th step, and the run refactorises after each of those whether one is written or not.
class CheckpointSchedule {
 public:
  static constexpr int wall_time_stride = 10;
  explicit CheckpointSchedule(const model::OutputSpec& output) : output_(output), last_(Clock::now()) {}
  /// Whether a checkpoint may follow `step`: the run refactorises after it (step-driven, never wall time).
  bool may_land(int step, int steps) const;
  bool due(int step, int steps) const;
  void written() { last_ = Clock::now(); }

 private:
  model::OutputSpec output_;
  Clock::time_point last_;
};

/// The checkpoint to resume from, checked against the run: the same scene, step size and terms.
/// @throws CheckpointError (core/run/simulate.hpp) naming the file and why.
Checkpoint load_checkpoint(const CheckpointStore& store, const model::Model& m,
                           const std::vector<time::Term*>& terms);

/// The checkpoint of the run at the end of step s.step.
Checkpoint checkpoint_of(const model::Model& m, const time::State& s, const std::vector<time::Term*>& terms,
                         const model::Summary& sum, const Recorder& recorder,
                         const StepControllerState* controller = nullptr);

}  // namespace stoss::run
