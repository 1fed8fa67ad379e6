#pragma once
/// @file JobFiles: the one place that turns a job into paths, DIR/jobs/<id>/{log.txt, result.h5,
/// result.xdmf}. Paths are built only from a JobId (validated hex), never from request text.

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

  /// Creates the job's directory and removes what an interrupted attempt left behind (results, not the log).
  void prepare_attempt(const JobId& id) const;
  /// Removes what a canceled or failed run left (result.h5.partial, result.incomplete.h5): never served.
  void discard_partial(const JobId& id) const;
  /// Removes the job's directory and everything in it.
  void remove(const JobId& id) const;

 private:
  std::filesystem::path root_;
};

}  // namespace stoss::server::jobs
