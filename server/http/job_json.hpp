#pragma once
/// @file The job JSON of docs/api.md: id, kind, status, times, progress, effects, summary, error, links
/// (and a study job's parameters as `study`).

#include <nlohmann/json.hpp>

#include "server/jobs/job.hpp"

namespace stoss::server::http {

/// What GET /v1/jobs/{id} returns for `job`. `before_run` is what POST found before the run
/// (scene::before_run_json): its warnings and choices are shown, and its estimate is the ETA until the
/// run measures its own; null for a job without it (queued by an older server).
nlohmann::json job_json(const jobs::Job& job, const nlohmann::json& before_run = nullptr);

}  // namespace stoss::server::http
