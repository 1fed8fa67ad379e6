#include "core/run/recorder.hpp"

namespace stoss::run {

void Recorder::step(const model::StepRow& row) {
  observer_.step(row);
  if (store_) rows_.push_back(row);
}

void Recorder::frame(int step, const model::Frame& frame) {
  observer_.frame(frame);
  if (!store_) return;
  store_->write_frame(static_cast<int>(frame_steps_.size()), frame);
  frame_steps_.push_back(step);
}

void Recorder::replay(const Checkpoint& c) {
  size_t k = 0;
  for (const model::StepRow& row : c.rows) {
    observer_.step(row);
    for (; k < c.frame_steps.size() && c.frame_steps[k] == row.step; ++k)
      observer_.frame(with_stresses(store_->read_frame(static_cast<int>(k)), problem_));
  }
  rows_ = c.rows;
  frame_steps_ = c.frame_steps;
}

}  // namespace stoss::run
