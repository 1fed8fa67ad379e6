#pragma once
/// @file The job JSON of docs/api.md: id, kind, status, times, progress, effects, summary, error, links
/// (and a study job's parameters as `study`).

#include <nlohmann/json.hpp>

#include "server/jobs/job.hpp"

namespace stoss::server::http {

/// What GET /v1/jobs/{id} returns for `job`.
nlohmann::json job_json(const jobs::Job& job);

}  // namespace stoss::server::http
