#pragma once
/// @file Study jobs (POST /v1/studies): the parameters the store keeps, the sweep of core/study run as a
/// job (progress as runs done of runs total, cancel honoured between and within runs, the table written to
/// study.json), and the table read back for GET /v1/jobs/{id}/study.

#include <atomic>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string_view>

#include "core/model/model.hpp"
#include "core/study/study.hpp"
#include "server/jobs/clock.hpp"
#include "server/jobs/job_files.hpp"
#include "server/jobs/running/executor.hpp"

namespace stoss::server::jobs {

/// The scheme named `name` (energy_momentum, midpoint, hht), or nullopt.
std::optional<model::Scheme> parse_scheme(std::string_view name);

/// A study's parameters as stored with its job: {"steps": [h...], "schemes": [name...], "reference_step": H}.
nlohmann::json study_params_json(const study::Options& options);
/// The options of study_params_json, read back. Throws std::invalid_argument on a malformed document.
study::Options study_options(const nlohmann::json& params);

/// Runs of a study: the reference run plus one per scheme and step.
int study_run_count(const study::Options& options);

/// A table written by study::to_json read back (a null error is NaN), for study::to_csv and to_markdown.
study::Result study_result_from_json(const nlohmann::json& table);

/// What a study run needs from its executor.
struct StudyContext {
  const AttemptFiles& files;  ///< of the attempt running the study
  const Clock& clock;
  Millis progress_interval;  ///< least time between two progress reports within a run
  std::ostream& log;         ///< one line per run
  const std::atomic<bool>& cancel;
  const ProgressSink& progress;
};

/// Runs study job `job` on `model` (its scene, loaded) as study::run does: the reference, then every
/// scheme × step, each row measured against the reference. Reports progress with step/steps counting runs.
/// Succeeded: study.json written (atomically) and a study summary. Canceled: when `cancel` is set, within
/// the run in progress. A sweep run that fails is a row with completed = false; a reference run that fails
/// throws (the job fails with the reason).
Outcome run_study_job(const Job& job, const model::Model& model, const StudyContext& context);

}  // namespace stoss::server::jobs
