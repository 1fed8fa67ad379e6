#pragma once
/// @file Checkpoints of a run (docs/results.md, "Checkpoints"): the full state at the end of a step, so
/// that a run stopped by a crash goes on from there and ends with the result it would have had.
///
/// A run's checkpoint directory (output::checkpoint_directory_name in a result directory) holds
///   state.h5      the last checkpoint (format stoss-checkpoint/1; written as state.h5.tmp, fsync'd, renamed)
///   frame_<k>.h5  frame k of the run (written once each, fsync'd before the next checkpoint names it)
/// state.h5:
///   /             attributes format, step, time, step_size, summary_* (the run's accumulators: Newton
///                 iterations, drifts, penetrations)
///   /scene        uint8 [bytes]: the resolved scene JSON
///   /state/x, /state/v, /state/a    [3N] float64: positions, velocities, the scheme's accelerations
///   /terms/<k>    attribute name; reals/<array> float64, integers/<array> int64 (time::TermState)
///   /series/step [S] int64, /series/time [S], /series/values [S, row size]: every row so far, step 0 too
///   /frames/step [K] int64: the step of each frame so far
///   /controller   with time.tolerance only: attributes next_step, previous_step, has_history
///                 (StepControllerState)

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/model/observer.hpp"
#include "core/output/result_writer.hpp"
#include "core/run/step_control.hpp"
#include "core/time/scheme.hpp"
#include "core/time/term.hpp"

namespace stoss::run {

inline constexpr const char* checkpoint_format = "stoss-checkpoint/1";

/// The state of a run at the end of a converged step: what it needs to go on as if it had never stopped.
struct Checkpoint {
  std::string scene;     ///< model.scene of the run (resolved): a checkpoint resumes that scene only
  time::State state;     ///< x, v, a, t and the step index
  double step_size = 0;  ///< time.step (step reduction keeps no state from one step to the next)
  /// Name and history of every term, in run order.
  std::vector<std::pair<std::string, time::TermState>> terms;
  model::Summary summary;            ///< accumulators so far: Newton iterations, drifts, penetrations
  std::vector<model::StepRow> rows;  ///< the series so far, step 0 included
  std::vector<int> frame_steps;      ///< the step of every frame so far (frame k in frame_<k>.h5)
  std::optional<StepControllerState> controller;  ///< with time.tolerance: the step controller's state
};

/// A run's checkpoint directory.
/// @note A crash at any moment leaves either the previous checkpoint or the new one, never a torn one:
///       state.h5 is renamed into place only after it and the frames it names are on disk.
class CheckpointStore {
 public:
  explicit CheckpointStore(std::filesystem::path directory) : directory_(std::move(directory)) {}

  const std::filesystem::path& directory() const { return directory_; }
  std::filesystem::path state_file() const { return directory_ / "state.h5"; }
  /// Whether the directory holds a checkpoint.
  bool exists() const;
  /// Writes frame k (a fresh file; the next write() syncs it before naming it).
  void write_frame(int k, const model::Frame& frame);
  /// Writes state.h5 through state.h5.tmp, fsync'd with the frames written since the last call, then renamed.
  void write(const Checkpoint& checkpoint);
  /// The last checkpoint. @throws std::runtime_error naming the file and what is wrong with it.
  Checkpoint read() const;
  /// Whether frame k's file is there.
  bool has_frame(int k) const;
  /// Frame k, as written by write_frame. @throws std::runtime_error naming the file.
  model::Frame read_frame(int k) const;
  /// Removes the directory and everything in it.
  void remove() const;

 private:
  std::filesystem::path frame_file(int k) const;

  std::filesystem::path directory_;
  std::vector<std::filesystem::path> unsynced_;  ///< frames written since the last checkpoint
};

}  // namespace stoss::run
