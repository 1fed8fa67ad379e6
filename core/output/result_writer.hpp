#pragma once
/// @file The observer that writes a run to DIR/result.h5 (layout: core/output/layout.hpp) and the XDMF
/// sidecars DIR/result.xdmf and DIR/result_mesh.xdmf.

#include <filesystem>
#include <memory>

#include "core/model/observer.hpp"

namespace stoss::output {

/// File names inside a result directory.
inline constexpr const char* result_file_name = "result.h5";                 ///< complete runs only
inline constexpr const char* partial_file_name = "result.h5.partial";        ///< while a run writes
inline constexpr const char* incomplete_file_name = "result.incomplete.h5";  ///< canceled or failed runs
inline constexpr const char* xdmf_file_name = "result.xdmf";  ///< time series sidecar, complete runs
inline constexpr const char* xdmf_mesh_file_name =
    "result_mesh.xdmf";  ///< reference mesh sidecar, complete runs
/// The run's checkpoints (core/run/checkpoint.hpp) while it goes (a job's directory, stoss run's -o DIR).
inline constexpr const char* checkpoint_directory_name = "checkpoint";

/// Writes one run into a directory. While the run goes the data is in result.h5.partial;
/// end() renames it to result.h5 only when the run completed (after writing the XDMF sidecars),
/// else to result.incomplete.h5 with complete = 0. So result.h5 exists only when complete.
/// @note Series rows are buffered and written every rows_per_flush steps; frames at once.
/// @note Not thread-safe: one writer serves one run on one thread at a time.
class ResultWriter : public model::Observer {
 public:
  /// Series rows held in memory between appends to the file.
  static constexpr int rows_per_flush = 64;

  explicit ResultWriter(std::filesystem::path directory);
  /// Without end(): closes the file and leaves only result.h5.partial behind.
  ~ResultWriter() override;
  ResultWriter(const ResultWriter&) = delete;
  ResultWriter& operator=(const ResultWriter&) = delete;

  /// Creates the directory, removes results of an earlier run in it, opens result.h5.partial
  /// and writes the root attributes, /mesh and the empty /series and /frames datasets.
  void begin(const model::Model& model, const model::SeriesLayout& layout) override;
  /// Buffers one row; throws std::invalid_argument when its size is not layout.row_size().
  void step(const model::StepRow& row) override;
  /// Writes one frame (group /frames/<k>: position, velocity, displacement, and contact_pressure,
  /// cauchy_stress and von_mises when the frame carries them); throws std::invalid_argument when a field
  /// has the wrong size, or when contact_pressure or the stresses are in some frames and not in others
  /// (the first frame decides).
  void frame(const model::Frame& frame) override;
  /// Flushes, writes wall_seconds and complete, closes and renames (see the class comment).
  void end(const model::Summary& summary) override;

  const std::filesystem::path& directory() const { return directory_; }

 private:
  struct Run;
  std::filesystem::path directory_;
  std::unique_ptr<Run> run_;  ///< the open run: between begin() and end()
};

}  // namespace stoss::output
