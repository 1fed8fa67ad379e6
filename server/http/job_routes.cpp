#include "server/http/job_routes.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>

#include "core/output/durable_file.hpp"
#include "core/scene/scene.hpp"
#include "core/scene/warnings.hpp"
#include "server/common/sha256.hpp"
#include "server/http/job_json.hpp"
#include "server/http/route_support.hpp"
#include "server/http/scene_check.hpp"
#include "server/http/study_check.hpp"
#include "server/jobs/running/study_job.hpp"

namespace stoss::server::http {

namespace {

using httplib::Request;
using httplib::Response;

constexpr std::size_t max_idempotency_key = 255;

std::optional<std::string> idempotency_key(const Request& req) {
  if (!req.has_header("Idempotency-Key")) return std::nullopt;
  std::string key = req.get_header_value("Idempotency-Key");
  const bool visible_ascii = std::all_of(key.begin(), key.end(), [](char c) { return c > 0x20 && c < 0x7f; });
  if (key.empty() || key.size() > max_idempotency_key || !visible_ascii)
    fail(400, "bad-idempotency-key", "Bad Idempotency-Key",
         "Idempotency-Key must be 1 to 255 visible ASCII characters");
  return key;
}

/// DIR/jobs/<id>/before_run.json: the warnings, choices and estimates POST found (scene::before_run_json),
/// kept beside the job's log for its job JSON.
std::filesystem::path before_run_file(const App& app, const jobs::JobId& id) {
  return app.files.dir(id) / "before_run.json";
}

/// The job JSON of `job` with what POST found before the run, when it was kept.
nlohmann::json job_body(const App& app, const jobs::Job& job) {
  const auto text = read_file(before_run_file(app, job.id));
  return job_json(job, text ? nlohmann::json::parse(*text, nullptr, false) : nlohmann::json());
}

/// Stores `job` (201, or 200 for a repeated Idempotency-Key with the same body) and wakes the workers;
/// a new job keeps `before_run` in its directory.
void queue_job(App& app, const jobs::NewJob& job, const nlohmann::json& before_run, Response& res) {
  const jobs::CreateResult created = app.store.create(job, app.limits.max_queued);
  if (created.outcome == jobs::CreateResult::Outcome::created) try {
      std::filesystem::create_directories(app.files.dir(created.job->id));
      output::write_durably(before_run_file(app, created.job->id), before_run.dump());
    } catch (const std::exception& e) {  // the job is queued: without the file its JSON has no warnings
      std::cerr << "job " << created.job->id.str() << ": cannot keep its warnings: " << e.what() << "\n";
    }
  using Outcome = jobs::CreateResult::Outcome;
  switch (created.outcome) {
    case Outcome::queue_full:
      fail(503, "queue-full", "Queue full",
           "the queue holds its limit of " + std::to_string(app.limits.max_queued) +
               " jobs (max_queued); retry later");
    case Outcome::key_conflict:
      fail(422, "idempotency-key-reused", "Idempotency-Key reused",
           "Idempotency-Key '" + *job.idempotency_key + "' was used for job " + created.job->id.str() +
               " with a different body");
    case Outcome::existing:
      return send_json(res, 200, job_body(app, *created.job));
    case Outcome::created:
      app.pool.notify();
      res.set_header("Location", "/v1/jobs/" + created.job->id.str());
      return send_json(res, 201, job_body(app, *created.job));
  }
}

/// A study's before-run JSON: the scene's warnings but those on /time/step (a study sweeps steps of its own),
/// its choices, no run-time estimate.
nlohmann::json study_before_run(const StudyRequest& study) {
  nlohmann::json found = scene::before_run_json(study.summary);
  nlohmann::json& warnings = found["warnings"];
  warnings.erase(std::remove_if(warnings.begin(), warnings.end(),
                                [](const nlohmann::json& w) { return w["pointer"] == "/time/step"; }),
                 warnings.end());
  found.erase("estimates");
  return found;
}

int list_limit(const Request& req) {
  if (!req.has_param("limit")) return 20;
  const std::string text = req.get_param_value("limit");
  const int limit = all_digits(text, 3) ? std::stoi(text) : 0;
  if (limit < 1 || limit > 200)
    fail(400, "bad-parameter", "Bad parameter", "limit must be an integer in [1, 200]");
  return limit;
}

std::optional<std::int64_t> list_cursor(const Request& req) {
  if (!req.has_param("cursor")) return std::nullopt;
  const std::string text = req.get_param_value("cursor");
  if (!all_digits(text, 18))
    fail(400, "bad-parameter", "Bad parameter", "cursor must be a next_cursor value from a listing");
  return std::stoll(text);
}

std::optional<jobs::Status> list_status(const Request& req) {
  if (!req.has_param("status")) return std::nullopt;
  auto status = jobs::parse_status(req.get_param_value("status"));
  if (!status)
    fail(400, "bad-parameter", "Bad parameter",
         "status must be one of queued, running, succeeded, failed, canceled");
  return status;
}

std::optional<std::string> list_verdict(const Request& req) {
  if (!req.has_param("verdict")) return std::nullopt;
  const std::string verdict = req.get_param_value("verdict");
  if (verdict != "ok" && verdict != "suspect")
    fail(400, "bad-parameter", "Bad parameter", "verdict must be one of ok, suspect");
  return verdict;
}

bool has_verdict(const jobs::Job& job, const std::string& verdict) {
  return job.summary && job.summary->is_object() && job.summary->value("verdict", "") == verdict;
}

}  // namespace

void submit_job(App& app, const Request& req, Response& res) {
  jobs::NewJob job;
  job.idempotency_key = idempotency_key(req);
  job.scene = parse_json_body(req, app.limits);
  job.body_hash = sha256_hex(job.scene.dump());  // of the scene as posted (idempotency)
  nlohmann::json resolved;
  const scene::Summary summary = check_scene(job.scene, app.limits, mesh_files(app), &resolved);
  job.scene = std::move(resolved);  // validated and resolved once: the worker runs it as stored
  job.effects = summary.effects;
  job.progress.steps = summary.steps;
  job.progress.end = job.scene.contains("time") ? job.scene["time"].value("end", 0.0) : 0.0;
  queue_job(app, job, scene::before_run_json(summary), res);
}

void submit_study(App& app, const Request& req, Response& res) {
  jobs::NewJob job;
  job.idempotency_key = idempotency_key(req);
  const nlohmann::json body = parse_json_body(req, app.limits);
  const StudyRequest study = check_study(body, app.limits, mesh_files(app));
  job.kind = jobs::Kind::study;
  job.body_hash = sha256_hex("study\n" + body.dump());  // never equal to a scene's hash
  job.scene = study.scene;
  job.study = jobs::study_params_json(study.options);
  job.effects = study.summary.effects;
  job.progress.steps = study.runs;
  job.progress.end = study.scene.value("time", nlohmann::json::object()).value("end", 0.0);
  queue_job(app, job, study_before_run(study), res);
}

void list_jobs(App& app, const Request& req, Response& res) {
  const std::optional<std::string> verdict = list_verdict(req);
  const jobs::Page page = app.store.list(list_status(req), list_limit(req), list_cursor(req));
  nlohmann::json body = {{"jobs", nlohmann::json::array()}, {"next_cursor", nullptr}};
  for (const auto& job : page.jobs)
    if (!verdict || has_verdict(job, *verdict)) body["jobs"].push_back(job_body(app, job));
  if (page.next_cursor) body["next_cursor"] = std::to_string(*page.next_cursor);
  send_json(res, 200, body);
}

void get_job(App& app, const Request& req, Response& res) {
  send_json(res, 200, job_body(app, find_job(app, req)));
}

void cancel_job(App& app, const Request& req, Response& res) {
  const jobs::Job job = find_job(app, req);
  if (jobs::is_terminal(job.status))  // canceled included: nothing is left to cancel
    fail(409, "already-finished", "Job already finished",
         "job " + job.id.str() + " already " + jobs::to_string(job.status));
  const jobs::CancelResult result = app.store.request_cancel(job.id);
  using Outcome = jobs::CancelResult::Outcome;
  switch (result.outcome) {
    case Outcome::not_found:
      fail(404, "unknown-job", "Unknown job", "no job " + job.id.str());
    case Outcome::already_done:
      fail(409, "already-finished", "Job already finished",
           "job " + job.id.str() + " already " + jobs::to_string(result.job->status));
    case Outcome::requested:
      app.pool.cancel(job.id);
      [[fallthrough]];
    case Outcome::canceled:
      return send_json(res, 202, job_body(app, *result.job));
  }
}

void delete_job(App& app, const Request& req, Response& res) {
  const jobs::Job job = find_job(app, req);
  switch (app.store.remove(job.id)) {
    case jobs::RemoveOutcome::not_found:
      fail(404, "unknown-job", "Unknown job", "no job " + job.id.str());
    case jobs::RemoveOutcome::not_finished:
      fail(409, "not-finished", "Job not finished",
           "job " + job.id.str() + " is " + jobs::to_string(job.status) + "; cancel it first");
    case jobs::RemoveOutcome::removed:
      app.files.remove(job.id);
      res.status = 204;
  }
}

void get_scene(App& app, const Request& req, Response& res) {
  const std::string resolved = req.has_param("resolved") ? req.get_param_value("resolved") : "false";
  if (resolved != "true" && resolved != "false")
    fail(400, "bad-parameter", "Bad parameter", "resolved must be true or false");
  const jobs::Job job = find_job(app, req);
  // Stored resolved at POST (every default filled in); ?resolved=true also resolves the scene of a job
  // queued by an older server, which stored it as posted.
  const auto stored = app.store.scene(job.id);
  if (!stored) fail(404, "unknown-job", "Unknown job", "no job " + job.id.str());
  if (resolved == "false") return send_json(res, 200, *stored);
  try {
    send_json(res, 200, scene::load(*stored, mesh_files(app)).scene);
  } catch (const std::exception& e) {
    fail(500, "internal", "Scene cannot be resolved", e.what());
  }
}

}  // namespace stoss::server::http
