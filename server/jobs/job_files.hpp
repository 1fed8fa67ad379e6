#pragma once
/// @file JobFiles: the one place that turns a job into paths. Each attempt of a job writes only in a folder
/// of its own, DIR/jobs/<id>/attempt-<n>/ (AttemptFiles: log.txt, result.h5, result.xdmf for a simulation,
/// study.json for a study, outcome.json), so an attempt that lost its lease cannot touch the files of the
/// attempt that replaced it; the store names the attempt a finished job published (Job::result_attempt),
/// and that folder is what the routes serve. Paths are built only from a JobId (validated hex) and attempt
/// numbers, never from request text.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "core/output/result_writer.hpp"
#include "core/scene/scene.hpp"
#include "server/jobs/id.hpp"
#include "server/jobs/store/store.hpp"

namespace stoss::server::jobs {

/// How an attempt ended, in its folder: written last, once the attempt's files are final.
inline constexpr const char* outcome_file_name = "outcome.json";

/// An outcome as outcome.json holds it, and back.
nlohmann::json outcome_json(const Outcome& outcome);
Outcome outcome_from_json(const nlohmann::json& j);

/// The folder of one attempt of a job (or, for a job that ended before attempts had folders, the job's
/// folder itself).
class AttemptFiles {
 public:
  explicit AttemptFiles(std::filesystem::path dir) : dir_(std::move(dir)) {}

  const std::filesystem::path& dir() const { return dir_; }
  /// The attempt's log (GET /v1/jobs/{id}/log serves every attempt's, in order: JobFiles::read_log).
  std::filesystem::path log() const { return dir_ / "log.txt"; }
  /// The complete result; it exists only after the run completed (output::ResultWriter writes
  /// result.h5.partial and renames it when the run completed, to result.incomplete.h5 otherwise).
  std::filesystem::path result() const { return dir_ / output::result_file_name; }
  std::filesystem::path xdmf() const { return dir_ / output::xdmf_file_name; }
  std::filesystem::path xdmf_mesh() const { return dir_ / output::xdmf_mesh_file_name; }
  /// The attempt's checkpoints (core/run/checkpoint.hpp), seeded from the attempt before (prepare).
  std::filesystem::path checkpoint() const { return dir_ / output::checkpoint_directory_name; }
  /// A study's table (study::to_json); it exists only after the study completed.
  std::filesystem::path study() const { return dir_ / "study.json"; }
  std::filesystem::path study_partial() const { return dir_ / "study.json.partial"; }
  std::filesystem::path outcome_file() const { return dir_ / outcome_file_name; }

  /// Removes what a canceled or failed run left (result.h5.partial, result.incomplete.h5,
  /// study.json.partial): never served.
  void discard_partial() const;
  /// Writes a study's table as study.json: to study.json.partial, synced to disk, then renamed, so the
  /// table appears only complete. Throws std::system_error when it cannot.
  void write_study(const std::string& text) const;
  /// Writes outcome.json (through a temporary name and a rename). Throws std::system_error when it cannot.
  void write_outcome(const Outcome& outcome) const;
  /// The outcome of this attempt's run when it succeeded and its result is complete (result.h5, or
  /// study.json for a study); nullopt otherwise.
  std::optional<Outcome> succeeded() const;

 private:
  std::filesystem::path dir_;
};

class JobFiles {
 public:
  /// `data_dir` is the server's --data directory.
  explicit JobFiles(std::filesystem::path data_dir)
      : root_(data_dir / "jobs"), meshes_(std::move(data_dir) / "meshes") {}

  std::filesystem::path dir(const JobId& id) const { return root_ / id.str(); }
  /// DIR/jobs/<id>/attempt-<attempt>/.
  AttemptFiles attempt(const JobId& id, int attempt) const;
  /// The folder whose files the routes serve for `job`: the attempt the store says it published, else the
  /// job's latest attempt (running, or ended without publishing), else the job's folder (a job that ended
  /// before attempts had folders).
  AttemptFiles served(const Job& job) const;
  /// The outcome of the newest attempt before `attempt` whose run succeeded with a complete result (its
  /// lease lapsed before it could report), result_attempt naming the attempt folder that holds it.
  std::optional<Outcome> completed_before(const JobId& id, int attempt) const;
  /// Every attempt's log, in attempt order (the log of a job that ran before attempts had folders first).
  std::string read_log(const JobId& id) const;

  /// DIR/meshes: the mesh files posted to /v1/meshes, named <sha256 of the bytes>.msh or .inp; written once
  /// (to a temporary name, then renamed), never changed, so a job naming one by id stays reproducible.
  std::filesystem::path meshes() const { return meshes_; }
  /// The stored file of a mesh id; nullopt unless `id` is 64 lowercase hex digits and the file exists.
  std::optional<std::filesystem::path> stored_mesh(const std::string& id) const;
  /// Mesh files for scene::load: "mesh": {"id": ...} resolved by stored_mesh, no "file".
  scene::MeshFiles mesh_files() const;

  /// Creates the folder of attempt `attempt` and returns it. Removes what an earlier run of the same
  /// attempt number (released at a shutdown) left behind, but not its log or checkpoint; when it has no
  /// checkpoint, copies the newest earlier attempt's last checkpoint into it (seed_checkpoint).
  AttemptFiles prepare_attempt(const JobId& id, int attempt) const;
  /// Once attempt `attempt` recorded a succeeded outcome, removes the checkpoints and partial files of it
  /// and of the attempts before it whose job process no longer runs here (one stopped past its lease
  /// keeps its files): any later attempt adopts that outcome instead of resuming, and none is ever served.
  /// Logs, outcomes and complete results stay (a rescuer may be adopting one).
  void prune_through(const JobId& id, int attempt) const;
  /// Removes the job's directory and everything in it.
  void remove(const JobId& id) const;

 private:
  /// Copies the last checkpoint of the newest attempt before `attempt` that has one (or of the job's
  /// folder, from before attempts had folders) into `into`: state.h5 first, then the frames, each to a
  /// temporary name and renamed. The source attempt may still be running (its lease lost): it only ever
  /// replaces state.h5 by a rename and writes frames past the ones its state.h5 names, so the copy of
  /// state.h5 names frames that are complete and stay as they are; frames copied past those are rewritten
  /// by the resumed run before a checkpoint of its own names them.
  void seed_checkpoint(const JobId& id, int attempt, const AttemptFiles& into) const;

  std::filesystem::path root_;
  std::filesystem::path meshes_;
};

}  // namespace stoss::server::jobs
