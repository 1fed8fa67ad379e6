#pragma once
/// @file JobFiles: the one place that turns a job into paths, DIR/jobs/<id>/{log.txt, result.h5,
/// result.xdmf} for a simulation, DIR/jobs/<id>/{log.txt, study.json} for a study. Paths are built only from
/// a JobId (validated hex), never from request text.

#include <filesystem>

#include "core/output/result_writer.hpp"
#include "server/jobs/id.hpp"

namespace stoss::server::jobs {

class JobFiles {
 public:
  /// `data_dir` is the server's --data directory.
  explicit JobFiles(std::filesystem::path data_dir) : root_(std::move(data_dir) / "jobs") {}

  std::filesystem::path dir(const JobId& id) const { return root_ / id.str(); }
  std::filesystem::path log(const JobId& id) const { return dir(id) / "log.txt"; }
  /// The complete result; it exists only after a run completed (output::ResultWriter writes
  /// result.h5.partial and renames it when the run completed, to result.incomplete.h5 otherwise).
  std::filesystem::path result(const JobId& id) const { return dir(id) / output::result_file_name; }
  std::filesystem::path xdmf(const JobId& id) const { return dir(id) / output::xdmf_file_name; }
  /// A study's table (study::to_json); it exists only after the study completed (written as
  /// study.json.partial, then renamed).
  std::filesystem::path study(const JobId& id) const { return dir(id) / "study.json"; }
  std::filesystem::path study_partial(const JobId& id) const { return dir(id) / "study.json.partial"; }

  /// Creates the job's directory and removes what an interrupted attempt left behind (results, not the log).
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
};

}  // namespace stoss::server::jobs
