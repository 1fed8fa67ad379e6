#include "core/run/checkpoint_schedule.hpp"

#include "core/run/simulate.hpp"

namespace stoss::run {

bool CheckpointSchedule::may_land(int step, int steps) const {
  if (step >= steps) return false;
  return step % (output_.checkpoint_every > 0 ? output_.checkpoint_every : wall_time_stride) == 0;
}

bool CheckpointSchedule::due(int step, int steps) const {
  if (!may_land(step, steps)) return false;
  return output_.checkpoint_every > 0 || seconds_since(last_) >= output_.checkpoint_seconds;
}

Checkpoint load_checkpoint(const CheckpointStore& store, const model::Model& m,
                           const std::vector<time::Term*>& terms) {
  Checkpoint c;
  try {
    c = store.read();
  } catch (const std::exception& e) {
    throw CheckpointError("cannot resume from " + store.state_file().string() + ": " + e.what());
  }
  const auto refuse = [&](const std::string& why) {
    throw CheckpointError("cannot resume from " + store.state_file().string() + ": " + why);
  };
  if (c.scene != m.scene.dump()) refuse("it was written for another scene");
  if (c.step_size != m.time.step) refuse("it was written with another time.step");
  if (c.terms.size() != terms.size())
    refuse("it holds " + std::to_string(c.terms.size()) + " terms, the run has " +
           std::to_string(terms.size()));
  for (size_t k = 0; k < terms.size(); ++k)
    if (c.terms[k].first != terms[k]->name()) refuse("term " + std::to_string(k) + " is " + c.terms[k].first);
  if (c.state.x.size() != m.dof_count() || c.state.v.size() != m.dof_count() ||
      c.state.a.size() != m.dof_count())
    refuse("its state does not have " + std::to_string(m.dof_count()) + " dofs");
  if (c.rows.empty() || c.rows.back().step != c.state.step) refuse("its series does not end at its step");
  if (m.time.adaptive() && !c.controller) refuse("it holds no step controller state (time.tolerance)");
  for (size_t k = 0; k < c.frame_steps.size(); ++k)
    if (!store.has_frame(static_cast<int>(k))) refuse("frame " + std::to_string(k) + " is missing");
  return c;
}

Checkpoint checkpoint_of(const model::Model& m, const time::State& s, const std::vector<time::Term*>& terms,
                         const model::Summary& sum, const Recorder& recorder,
                         const StepControllerState* controller) {
  Checkpoint c;
  c.scene = m.scene.dump();
  c.state = s;
  c.step_size = m.time.step;
  for (const time::Term* t : terms) c.terms.emplace_back(t->name(), t->save_state());
  c.summary = sum;
  c.rows = recorder.rows();
  c.frame_steps = recorder.frame_steps();
  if (controller) c.controller = *controller;
  return c;
}

}  // namespace stoss::run
