#pragma once
/// @file SeriesRecorder: a job's series as its run goes, for partial results (issue 10): every converged
/// step appended to series.partial.jsonl in the job's directory (flushed a few times a second and at the
/// end), so the series and a summary up to the last completed step can be read while the job runs, and
/// after it failed or was canceled. It also measures the friction balance for the job summary:
/// the Coulomb work dissipated and the drift of total energy + dissipated work.

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/model/observer.hpp"
#include "server/jobs/clock.hpp"

namespace stoss::server::jobs {

/// Name of the partial series file in a job's directory.
inline constexpr const char* partial_series_file = "series.partial.jsonl";

class SeriesRecorder : public model::Observer {
 public:
  /// Writes to `path` (truncated); `flush_every` ms between flushes, the first steps (0 and 1) at once: a
  /// job process killed once it has shown progress leaves a series, and a summary, to read.
  explicit SeriesRecorder(const std::filesystem::path& path, Millis flush_every = 250);

  void begin(const model::Model& model, const model::SeriesLayout& layout) override;
  void step(const model::StepRow& row) override;
  void end(const model::Summary& summary) override;

  /// The run's summary, once end() was called (also for a run that failed: the core reports it first).
  const std::optional<model::Summary>& summary() const { return summary_; }
  /// With a dissipated_energy series (frictional contact): the work dissipated by the last step, and
  /// max over steps |H_n + D_n − H_0| / |H_0| (H total energy, D dissipated work).
  std::optional<double> dissipated_energy() const;
  std::optional<double> energy_plus_dissipated_drift() const;

 private:
  std::ofstream out_;
  std::chrono::steady_clock::time_point last_flush_;
  Millis flush_every_;
  static constexpr long long flushed_at_once = 1;  ///< steps up to this one are flushed as they come
  int total_ = -1, dissipated_ = -1, work_ = -1;   ///< value offsets in a row (work_: external_work)
  std::optional<double> initial_energy_, last_dissipated_;
  double balance_drift_ = 0;
  std::optional<model::Summary> summary_;
};

/// The partial series of a job from its series.partial.jsonl: {"time": [...], <series>: [...], ...} as
/// output::series_json gives for a complete result, plus "completed": false and "summary" (steps, end_time,
/// initial_energy, energy_drift, newton_iterations up to the last recorded step; dissipated_energy and
/// energy_plus_dissipated_drift with friction; "verdict": null and "checks": [], as the checks are made when
/// the run ends). nullopt when the file is absent or has no step.
std::optional<nlohmann::json> read_partial_series(const std::filesystem::path& path);

/// The same series as CSV (columns as output::series_csv writes them); with `since`, only the rows of the
/// steps after it (the header always).
std::optional<std::string> partial_series_csv(const std::filesystem::path& path,
                                              std::optional<long long> since = std::nullopt);

/// `series` (output::series_json of a result, or read_partial_series) with a member "step": the step of
/// each row (t0 is step 0; a result has one row per step, a partial file names the step of each). With
/// `since`, every row-wise member keeps only the rows of the steps after it (GET …/series?since=STEP).
nlohmann::json series_after(nlohmann::json series, std::optional<long long> since);

/// `csv` (a header and one line per step from step 0, as output::series_csv writes it) without the lines
/// of steps 0 to `since`; unchanged without `since`.
std::string csv_rows_after(const std::string& csv, std::optional<long long> since);

}  // namespace stoss::server::jobs
