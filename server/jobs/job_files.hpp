#pragma once
/// @file JobFiles: the one place that turns a job into paths, DIR/jobs/<id>/{log.txt, result.h5,
/// result.xdmf} for a simulation, DIR/jobs/<id>/{log.txt, study.json} for a study. Paths are built only from
/// a JobId (validated hex), never from request text.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "core/output/result_writer.hpp"
#include "core/scene/scene.hpp"
#include "server/jobs/id.hpp"

namespace stoss::server::jobs {

/// Writes `bytes` to `path` (replacing it) and fsyncs the file, so that a rename after it cannot expose
/// a torn file. @throws std::system_error naming the path.
void write_synced(const std::filesystem::path& path, std::string_view bytes);

class JobFiles {
 public:
  /// `data_dir` is the server's --data directory.
  explicit JobFiles(std::filesystem::path data_dir)
      : root_(data_dir / "jobs"), meshes_(std::move(data_dir) / "meshes") {}

  std::filesystem::path dir(const JobId& id) const { return root_ / id.str(); }
  std::filesystem::path log(const JobId& id) const { return dir(id) / "log.txt"; }
  /// The complete result; it exists only after a run completed (output::ResultWriter writes
  /// result.h5.partial and renames it when the run completed, to result.incomplete.h5 otherwise).
  std::filesystem::path result(const JobId& id) const { return dir(id) / output::result_file_name; }
  std::filesystem::path xdmf(const JobId& id) const { return dir(id) / output::xdmf_file_name; }
  /// The run's checkpoints (core/output/checkpoint.hpp): kept across attempts, so that a retried attempt goes
  /// on from the last one; removed once the job succeeded or failed in the solver.
  std::filesystem::path checkpoint(const JobId& id) const { return dir(id) / output::checkpoint_directory_name; }
  std::filesystem::path xdmf_mesh(const JobId& id) const { return dir(id) / output::xdmf_mesh_file_name; }

  /// DIR/meshes: the mesh files posted to /v1/meshes, named <sha256 of the bytes>.msh or .inp; written once
  /// (to a temporary name, then renamed), never changed, so a job naming one by id stays reproducible.
  std::filesystem::path meshes() const { return meshes_; }
  /// The stored file of a mesh id; nullopt unless `id` is 64 lowercase hex digits and the file exists.
  std::optional<std::filesystem::path> stored_mesh(const std::string& id) const;
  /// Mesh files for scene::load: "mesh": {"id": ...} resolved by stored_mesh, no "file".
  scene::MeshFiles mesh_files() const;
  /// A study's table (study::to_json); it exists only after the study completed (written as
  /// study.json.partial, then renamed).
  std::filesystem::path study(const JobId& id) const { return dir(id) / "study.json"; }
  std::filesystem::path study_partial(const JobId& id) const { return dir(id) / "study.json.partial"; }

  /// Creates the job's directory and removes what an interrupted attempt left behind (results; not the log,
  /// not the checkpoint).
  void prepare_attempt(const JobId& id) const;
  /// Removes what a canceled or failed run left (result.h5.partial, result.incomplete.h5,
  /// study.json.partial): never served.
  void discard_partial(const JobId& id) const;
  /// Writes a study's table as study.json: to study.json.partial, synced to disk, then renamed, so the
  /// table appears only complete. Throws std::system_error when it cannot.
  void write_study(const JobId& id, const std::string& text) const;
  /// Removes the job's directory and everything in it.
  void remove(const JobId& id) const;

 private:
  std::filesystem::path root_;
  std::filesystem::path meshes_;
};

}  // namespace stoss::server::jobs
