#pragma once
/// @file The one entry point of the core: run a model, report to an observer, stop when asked.

#include <atomic>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "core/model/model.hpp"
#include "core/model/observer.hpp"

namespace stoss {

/// Set from any thread to stop a run at the end of the current time step.
using CancelFlag = std::atomic<bool>;

/// A step that cannot be solved: names the step, the time and the residual history.
class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A checkpoint that cannot be resumed: unreadable, of another scene or step size, or missing a frame.
/// Thrown before the observer hears of the run, so a caller may remove the checkpoint and start over.
class CheckpointError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Checkpoints of a run (core/run/checkpoint.hpp, docs/results.md "Checkpoints").
struct Checkpoints {
  /// Where the run writes them: every model.output.checkpoint_every steps, or every checkpoint_seconds of
  /// wall time; empty: the run writes none. Every checkpoint makes the next step start with a fresh
  /// factorisation, so a run resumed from it computes what the run that went on computes.
  std::filesystem::path directory;
  /// Go on from the checkpoint in `directory` when there is one: the observer gets the series rows and
  /// frames up to it again, a log line "resumed from step N", then the steps after N only.
  bool resume = false;
};

/// Runs `model` from t = 0 (or from a checkpoint) to model.time.end. Throws SolverError when a step fails
/// (after observer.end with completed = false). Returns with completed = false when canceled.
/// @throws CheckpointError when the checkpoint to resume from is of another scene or unreadable.
model::Summary simulate(const model::Model& model, model::Observer& observer,
                        const CancelFlag* cancel = nullptr, const Checkpoints& checkpoints = {});

}  // namespace stoss
