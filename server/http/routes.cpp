#include "server/http/routes.hpp"

#include <malloc.h>

#include <atomic>
#include <fstream>
#include <iostream>
#include <memory>
#include <regex>

#include "core/output/durable_file.hpp"
#include "core/output/result_reader.hpp"
#include "core/scene/scene.hpp"
#include "core/scene/warnings.hpp"
#include "server/http/byte_range.hpp"
#include "server/http/job_json.hpp"
#include "server/http/problem.hpp"
#include "server/http/request_gate.hpp"
#include "server/http/scene_check.hpp"
#include "server/http/study_check.hpp"
#include "server/meshes/mesh_store.hpp"
#include "server/jobs/reporting/series_recorder.hpp"
#include "server/common/sha256.hpp"
#include "server/jobs/running/study_job.hpp"
#include "server/web/assets.hpp"

namespace stoss::server::http {

namespace {

using httplib::Request;
using httplib::Response;
using Route = RouteHandler;

constexpr const char* json_type = "application/json";
constexpr std::size_t max_idempotency_key = 255;

[[noreturn]] void fail(int status, const std::string& kind, const std::string& title,
                       const std::string& detail) {
  throw ProblemError(Problem{status, "urn:stoss:problem:" + kind, title, detail});
}

void send_json(Response& res, int status, const nlohmann::json& body) {
  res.status = status;
  res.set_content(dump(body), json_type);
}

/// The job named by the path's first capture; 404 for a malformed or unknown id (no lookup for the former).
jobs::Job find_job(App& app, const Request& req) {
  auto id = jobs::JobId::parse(req.matches[1].str());
  if (!id) fail(404, "unknown-job", "Unknown job", "no such job (job ids are 32 lowercase hex digits)");
  auto job = app.store.get(*id);
  if (!job) fail(404, "unknown-job", "Unknown job", "no job " + id->str());
  return *job;
}

/// 409 unless the job succeeded (its result files exist only then); `what` names them in the detail.
void require_succeeded(const jobs::Job& job, const std::string& what = "result") {
  if (job.status == jobs::Status::succeeded) return;
  const std::string status = jobs::to_string(job.status);
  const std::string why =
      jobs::is_terminal(job.status) ? "; it has no " + what : "; the " + what + " exists once it succeeded";
  fail(409, "no-result", "Job has no result", "job " + job.id.str() + " is " + status + why);
}

/// 409 for a study job, which has a table instead of a result file; then 409 unless the job succeeded.
void require_result_file(const jobs::Job& job) {
  if (job.kind == jobs::Kind::study)
    fail(409, "no-result", "Job has no result",
         "job " + job.id.str() + " is a study job; a study job has no result file; see /v1/jobs/" +
             job.id.str() + "/study");
  require_succeeded(job);
}

/// Gives freed memory back to the system (malloc_trim) when the last copy of a request's MeshFiles goes, if
/// the request used a stored mesh: the model built to check a scene on a large mesh frees hundreds of MB
/// that glibc would otherwise keep (docs/measurements.md, "Hardening numbers").
struct TrimAfterUse {
  std::atomic<bool> used{false};
  ~TrimAfterUse() {
    if (used) malloc_trim(0);
  }
};

/// Mesh files for the scene checks: a stored mesh is parsed once and its parsed form shared (MeshStore).
scene::MeshFiles mesh_files(App& app) {
  scene::MeshFiles files = app.files.mesh_files();
  files.parsed = [store = &meshes::MeshStore::at(app.files.meshes()),
                  limits = mesh::upload_limits(app.limits.max_nodes),
                  trim = std::make_shared<TrimAfterUse>()](const std::string& id) {
    trim->used = true;
    return store->parsed(id, limits);
  };
  return files;
}

std::optional<std::string> read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  return std::string(std::istreambuf_iterator<char>(in), {});
}

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

/// A study is a job of kind "study": progress counts runs; its table is served by get_study.
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

/// 1 to `max_length` ASCII digits.
bool all_digits(const std::string& text, std::size_t max_length) {
  return !text.empty() && text.size() <= max_length &&
         std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
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

/// ?verdict filters the store's page (the stores keep no verdict column): a page may hold fewer than
/// `limit` jobs, and next_cursor goes on where the store's page ended.
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

/// Streams a file from disk, honouring a single byte range (RFC 9110 §14: 206 with Content-Range, 416
/// with Content-Range: bytes */SIZE when unsatisfiable, lengths clamped to the file).
void stream_file(const Request& req, Response& res, const std::filesystem::path& path,
                 const std::string& type) {
  auto in = std::make_shared<std::ifstream>(path, std::ios::binary);
  std::error_code error;
  const auto size = static_cast<std::uint64_t>(std::filesystem::file_size(path, error));
  if (!*in || error) fail(500, "missing-result", "Result missing", "the result file cannot be read");
  const ByteRange range = resolve_range(req.get_header_value("Range"), size);
  if (range.kind == ByteRange::Kind::unsatisfiable) {
    res.set_header("Content-Range", "bytes */" + std::to_string(size));
    fail(416, "range-not-satisfiable", "Range Not Satisfiable",
         "the file has " + std::to_string(size) + " bytes; Range " + req.get_header_value("Range") +
             " selects none of them");
  }
  const std::uint64_t first = range.kind == ByteRange::Kind::partial ? range.first : 0;
  const std::uint64_t length = range.kind == ByteRange::Kind::partial ? range.length : size;
  res.status = 200;
  if (range.kind == ByteRange::Kind::partial) {
    res.status = 206;
    res.set_header("Content-Range", "bytes " + std::to_string(first) + "-" + std::to_string(first + length - 1) +
                                        "/" + std::to_string(size));
  }
  res.set_content_provider(
      static_cast<std::size_t>(length), type,
      [in, first](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
        char buffer[1 << 16];
        in->seekg(static_cast<std::streamoff>(first + offset));
        in->read(buffer, static_cast<std::streamsize>(std::min(length, sizeof buffer)));
        const auto n = in->gcount();
        return n > 0 && sink.write(buffer, static_cast<std::size_t>(n));
      });
}

void get_result(App& app, const Request& req, Response& res) {
  const jobs::Job job = find_job(app, req);
  require_result_file(job);
  const auto path = app.files.served(job).result();
  std::error_code error;
  const auto size = std::filesystem::file_size(path, error);
  if (error)
    fail(500, "missing-result", "Result missing",
         "job " + job.id.str() + " succeeded but its result is gone");
  const std::string etag = "\"" + job.id.str() + "-" + std::to_string(size) + "\"";
  res.set_header("ETag", etag);
  res.set_header("Accept-Ranges", "bytes");
  res.set_header("Content-Disposition", "attachment; filename=\"result.h5\"");
  if (req.get_header_value("If-None-Match") == etag) {
    res.status = 304;
    return;
  }
  stream_file(req, res, path, "application/x-hdf5");
}

/// One of a succeeded job's XDMF sidecars, `path` of its directory, as an attachment named by the file.
void send_xdmf(App& app, const Request& req, Response& res,
               std::filesystem::path (jobs::AttemptFiles::*path)() const) {
  const jobs::Job job = find_job(app, req);
  require_result_file(job);
  const std::filesystem::path file = (app.files.served(job).*path)();
  auto text = read_file(file);
  if (!text)
    fail(500, "missing-result", "Result missing",
         "job " + job.id.str() + " succeeded but its " + file.filename().string() + " is gone");
  res.set_header("Content-Disposition", "attachment; filename=\"" + file.filename().string() + "\"");
  res.set_content(*text, "application/xml");
}

void get_result_xdmf(App& app, const Request& req, Response& res) {
  send_xdmf(app, req, res, &jobs::AttemptFiles::xdmf);
}

void get_result_mesh_xdmf(App& app, const Request& req, Response& res) {
  send_xdmf(app, req, res, &jobs::AttemptFiles::xdmf_mesh);
}

/// The `format` query parameter: `allowed[0]` when absent, 400 when not one of `allowed`.
std::string format_param(const Request& req, const std::vector<std::string>& allowed) {
  const std::string format = req.has_param("format") ? req.get_param_value("format") : allowed.front();
  if (std::find(allowed.begin(), allowed.end(), format) != allowed.end()) return format;
  std::string names;
  for (const auto& name : allowed) names += (names.empty() ? "" : ", ") + name;
  fail(400, "bad-parameter", "Bad parameter", "format must be one of " + names);
}

/// The `since` query parameter: the rows after this step are wanted; nullopt when absent.
std::optional<long long> since_param(const Request& req) {
  if (!req.has_param("since")) return std::nullopt;
  const std::string text = req.get_param_value("since");
  if (!all_digits(text, 9))
    fail(400, "bad-parameter", "Bad parameter", "since must be a step number, an integer in [0, 999999999]");
  return std::stoll(text);
}

/// A partial series' summary with the verdict and checks of the job's own summary once the job ended with
/// one (a canceled or failed run is judged too); a running job's stay null and [] (read_partial_series).
void with_job_verdict(nlohmann::json& series, const jobs::Job& job) {
  if (!job.summary || !job.summary->is_object() || !job.summary->contains("verdict")) return;
  series["summary"]["verdict"] = (*job.summary)["verdict"];
  series["summary"]["checks"] = job.summary->value("checks", nlohmann::json::array());
}

void get_series(App& app, const Request& req, Response& res) {
  const std::string format = format_param(req, {"json", "csv"});
  const std::optional<long long> since = since_param(req);
  const jobs::Job job = find_job(app, req);
  if (job.kind == jobs::Kind::simulation && job.status != jobs::Status::succeeded) {
    // Running, failed or canceled: the series up to the last completed step, marked completed: false.
    const auto partial = app.files.served(job).dir() / jobs::partial_series_file;
    if (format == "csv") {
      if (auto csv = jobs::partial_series_csv(partial, since)) {
        res.set_header("Stoss-Completed", "false");
        return res.set_content(*csv, "text/csv");
      }
    } else if (auto series = jobs::read_partial_series(partial)) {
      with_job_verdict(*series, job);
      return send_json(res, 200, jobs::series_after(std::move(*series), since));
    }
  }
  require_result_file(job);
  const auto path = app.files.served(job).result();
  if (format == "csv") return res.set_content(jobs::csv_rows_after(output::series_csv(path), since), "text/csv");
  send_json(res, 200, jobs::series_after(output::series_json(path), since));
}

/// A study job's table: JSON as written (study::to_json), CSV or Markdown made from it.
void get_study(App& app, const Request& req, Response& res) {
  const std::string format = format_param(req, {"json", "csv", "markdown"});
  const jobs::Job job = find_job(app, req);
  if (job.kind != jobs::Kind::study)
    fail(404, "not-a-study", "Not a study",
         "job " + job.id.str() +
             " is a simulation job; only a study job (POST /v1/studies) has a study table");
  require_succeeded(job, "study table");
  const auto text = read_file(app.files.served(job).study());
  if (!text)
    fail(500, "missing-result", "Result missing",
         "job " + job.id.str() + " succeeded but its study table is gone");
  if (format == "json") return res.set_content(*text, json_type);
  const study::Result table = jobs::study_result_from_json(nlohmann::json::parse(*text));
  if (format == "csv") return res.set_content(study::to_csv(table), "text/csv");
  res.set_content(study::to_markdown(table), "text/markdown; charset=utf-8");
}

void get_log(App& app, const Request& req, Response& res) {
  const jobs::Job job = find_job(app, req);
  res.set_content(app.files.read_log(job.id), "text/plain; charset=utf-8");
}

/// The format of a posted mesh: the `format` parameter, else what the bytes look like.
std::string mesh_format(const Request& req) {
  if (req.has_param("format")) return format_param(req, {"msh", "inp"});
  const std::string sniffed = meshes::sniff_mesh_format(req.body);
  if (sniffed.empty())
    fail(400, "bad-parameter", "Bad parameter",
         "cannot tell the mesh format from the body (a Gmsh file starts with $MeshFormat, an Abaqus/CalculiX "
         "deck with a *KEYWORD line); give format=msh or format=inp");
  return sniffed;
}

/// name → size (elements of a set, faces of a surface).
template <typename Map>
nlohmann::json sizes(const Map& named) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, items] : named) out[name] = items.size();
  return out;
}

/// 422 for a mesh file that is not usable, naming the line when there is one.
[[noreturn]] void invalid_mesh(const mesh::MeshFileError& e, const std::string& format) {
  Problem problem{422, "urn:stoss:problem:invalid-mesh", "Invalid mesh", e.what()};
  if (e.line > 0) problem.extra["line"] = e.line;
  problem.extra["format"] = format;
  throw ProblemError(problem);
}

/// POST /v1/meshes: the raw bytes of a .msh or .inp file, parsed once under the limits of --max-nodes (no
/// *INCLUDE), stored by content (201; 200 when the same bytes were stored before); 413 above
/// --max-mesh-store-bytes.
void post_mesh(App& app, const Request& req, Response& res) {
  if (req.body.size() > app.limits.max_body_bytes) throw ProblemError(body_too_large(app.limits.max_body_bytes, req.body.size()));
  const std::string format = mesh_format(req);
  if (req.body.empty()) fail(400, "empty-body", "Empty body", "the body is empty; send the bytes of a .msh or .inp file");
  meshes::StoredMesh stored;
  try {
    stored = meshes::MeshStore::at(app.files.meshes())
                 .store(req.body, format, mesh::upload_limits(app.limits.max_nodes),
                        app.limits.max_mesh_store_bytes);
  } catch (const mesh::MeshFileError& e) {
    invalid_mesh(e, format);
  } catch (const meshes::MeshStoreFull& e) {
    throw ProblemError(Problem{413,
                               "urn:stoss:problem:mesh-store-full",
                               "Mesh store full",
                               std::string(e.what()) + "; DELETE /v1/meshes/{id} of meshes no longer needed",
                               {{"limits", nlohmann::json::array({{{"name", "max_mesh_store_bytes"},
                                                                   {"limit", e.limit},
                                                                   {"value", e.used + e.size}}})}}});
  }
  if (stored.created) res.set_header("Location", "/v1/meshes/" + stored.id);
  send_json(res, stored.created ? 201 : 200,
            {{"id", stored.id},
             {"format", stored.format},
             {"nodes", stored.mesh->nodes.size()},
             {"elements", stored.mesh->hex8.size()},
             {"element_sets", sizes(stored.mesh->element_sets)},
             {"surfaces", sizes(stored.mesh->surfaces)}});
}

/// The stored file of the mesh id in the path's first capture; 404 when there is none.
std::filesystem::path find_mesh(App& app, const Request& req) {
  const std::string id = req.matches[1].str();
  const auto path = meshes::MeshStore::at(app.files.meshes()).path_of(id);
  if (!path)
    fail(404, "unknown-mesh", "Unknown mesh",
         "no mesh " + id.substr(0, 64) + " (mesh ids are 64 lowercase hex digits, as POST /v1/meshes answers)");
  return *path;
}

/// GET /v1/meshes/{id}: the stored file, byte for byte.
void get_mesh(App& app, const Request& req, Response& res) {
  const auto path = find_mesh(app, req);
  res.set_header("Content-Disposition", "attachment; filename=\"" + path.filename().string() + "\"");
  res.set_header("Cache-Control", "public, max-age=31536000, immutable");
  stream_file(req, res, path, "application/octet-stream");
}

/// DELETE /v1/meshes/{id}: 204, or 409 while a queued or running job names the mesh.
void delete_mesh(App& app, const Request& req, Response& res) {
  const std::string id = find_mesh(app, req).stem().string();
  const std::vector<jobs::JobId> users = app.store.active_jobs_using_mesh(id);
  if (!users.empty()) {
    nlohmann::json ids = nlohmann::json::array();
    for (const auto& job : users) ids.push_back(job.str());
    throw ProblemError(Problem{409,
                               "urn:stoss:problem:mesh-in-use",
                               "Mesh in use",
                               "mesh " + id + " is named by " + std::to_string(users.size()) +
                                   " queued or running job(s), the first " + users.front().str() +
                                   "; delete it once they ended (or cancel them)",
                               {{"jobs", ids}}});
  }
  if (!meshes::MeshStore::at(app.files.meshes()).remove(id))
    fail(404, "unknown-mesh", "Unknown mesh", "no mesh " + id);
  res.status = 204;
}

void validate_scene(App& app, const Request& req, Response& res) {
  const nlohmann::json scene = parse_json_body(req, app.limits);
  const scene::Summary s = check_scene(scene, app.limits, mesh_files(app));
  nlohmann::json body = {{"valid", true},          {"effects", s.effects}, {"nodes", s.nodes},
                         {"elements", s.elements}, {"dofs", s.dofs},       {"steps", s.steps},
                         {"frames", s.frames}};
  body.update(scene::before_run_json(s));
  send_json(res, 200, body);
}

void get_schema(App&, const Request&, Response& res) {
  res.set_content(dump(scene::schema()), "application/schema+json");
}

/// The scene of a job as it was posted (for a study: the study's scene); `?resolved=true` with every
/// default of the schema filled in.
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

/// api/openapi.yaml, as in the source tree this binary was built from.
void get_openapi(App&, const Request&, Response& res) {
  static const std::optional<std::string> text =
      read_file(std::filesystem::path(STOSS_SOURCE_DIR) / "api" / "openapi.yaml");
  if (!text) fail(500, "missing-file", "OpenAPI document missing", "api/openapi.yaml cannot be read");
  res.set_content(*text, "application/yaml");
}

/// The web page (docs/web.md); it asks for the token itself when the API answers 401.
void get_page(App&, const Request&, Response& res) {
  const auto page = web::find_asset("index.html");
  if (!page) fail(500, "internal", "Page missing", "index.html was not compiled in");
  res.set_header("Cache-Control", "no-cache");
  res.set_content(std::string(page->bytes), std::string(page->media_type));
}

/// A file of the page (its script and style, Debian's dygraphs), as compiled in.
void get_asset(App&, const Request& req, Response& res) {
  const std::string name = req.matches[1].str();
  const auto asset = web::find_asset(name);
  if (!asset) fail(404, "no-route", "Not Found", "the page has no file " + name.substr(0, 100));
  res.set_header("Cache-Control", "no-cache");
  res.set_content(std::string(asset->bytes), std::string(asset->media_type));
}

/// Whether some body of `scene` names a mesh file (the service refuses those: it reads no files).
bool names_mesh_file(const nlohmann::json& scene) {
  for (const auto& body : scene.value("bodies", nlohmann::json::array()))
    if (body.is_object() && body.value("mesh", nlohmann::json::object()).contains("file")) return true;
  return false;
}

/// The example scenes of api/examples (compiled in) that the service can run: name, title, scene.
void list_examples(App&, const Request&, Response& res) {
  static const nlohmann::json examples = [] {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& file : web::embedded_examples()) {
      const nlohmann::json scene = nlohmann::json::parse(file.bytes);
      if (names_mesh_file(scene)) continue;
      const std::string name(file.name.substr(0, file.name.rfind(".json")));
      list.push_back({{"name", name}, {"title", scene.value("name", name)}, {"scene", scene}});
    }
    return nlohmann::json{{"examples", list}};
  }();
  send_json(res, 200, examples);
}

void get_health(App&, const Request&, Response& res) {
  send_json(res, 200, {{"status", "ok"}});
}

void get_metrics(App& app, const Request&, Response& res) {
  res.set_content(app.metrics.render(app.store.count_by_status(), app.pool.running()),
                  "text/plain; version=0.0.4");
}

struct RouteEntry {
  RouteInfo info;
  Route handler;
};

/// The API: every route, as api/openapi.yaml names it.
const std::vector<RouteEntry>& route_table() {
  static const std::vector<RouteEntry> table = {
      {{"POST", "/v1/jobs", true}, submit_job},
      {{"GET", "/v1/jobs", true}, list_jobs},
      {{"GET", "/v1/jobs/{id}", true}, get_job},
      {{"DELETE", "/v1/jobs/{id}", true}, delete_job},
      {{"POST", "/v1/jobs/{id}/cancel", true}, cancel_job},
      {{"GET", "/v1/jobs/{id}/result", true}, get_result},
      {{"GET", "/v1/jobs/{id}/result.xdmf", true}, get_result_xdmf},
      {{"GET", "/v1/jobs/{id}/result_mesh.xdmf", true}, get_result_mesh_xdmf},
      {{"GET", "/v1/jobs/{id}/series", true}, get_series},
      {{"GET", "/v1/jobs/{id}/log", true}, get_log},
      {{"GET", "/v1/jobs/{id}/study", true}, get_study},
      {{"POST", "/v1/studies", true}, submit_study},
      {{"POST", "/v1/validate", true}, validate_scene},
      {{"POST", "/v1/meshes", true}, post_mesh},
      {{"GET", "/v1/meshes/{id}", true}, get_mesh},
      {{"DELETE", "/v1/meshes/{id}", true}, delete_mesh},
      {{"GET", "/v1/schema/scene", true}, get_schema},
      {{"GET", "/v1/jobs/{id}/scene", true}, get_scene},
      {{"GET", "/v1/openapi.yaml", true}, get_openapi},
      {{"GET", "/v1/examples", true}, list_examples},
      {{"GET", "/", false}, get_page},
      {{"GET", "/web/{asset}", false}, get_asset},
      {{"GET", "/healthz", false}, get_health},
      {{"GET", "/metrics", true}, get_metrics},
  };
  return table;
}

/// The httplib pattern of an OpenAPI path: a parameter ("{id}", "{asset}") captures one segment, "." is
/// literal.
std::string pattern_of(const std::string& path) {
  std::string pattern;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (path[i] == '{' && path.find('}', i) != std::string::npos) {
      pattern += "([^/]+)";
      i = path.find('}', i);
    } else {
      if (path[i] == '.') pattern += '\\';
      pattern += path[i];
    }
  }
  return pattern;
}

/// Every route with its compiled path pattern.
const std::vector<std::pair<std::regex, const RouteInfo*>>& route_patterns() {
  static const std::vector<std::pair<std::regex, const RouteInfo*>> patterns = [] {
    std::vector<std::pair<std::regex, const RouteInfo*>> out;
    for (const auto& r : route_table()) out.emplace_back(std::regex(pattern_of(r.info.path)), &r.info);
    return out;
  }();
  return patterns;
}

}  // namespace

const RouteInfo* find_route(const Request& req) {
  if (req.path.size() > 1024) return nullptr;
  const std::string method = req.method == "HEAD" ? "GET" : req.method;
  for (const auto& [pattern, info] : route_patterns())
    if (info->method == method && std::regex_match(req.path, pattern)) return info;
  return nullptr;
}

std::vector<std::string> allowed_methods(const std::string& path) {
  std::vector<std::string> methods;
  if (path.size() > 1024) return methods;
  for (const auto& [pattern, info] : route_patterns())
    if (std::regex_match(path, pattern) &&
        std::find(methods.begin(), methods.end(), info->method) == methods.end())
      methods.push_back(info->method);
  return methods;
}

std::vector<RouteInfo> routes() {
  std::vector<RouteInfo> out;
  for (const auto& r : route_table()) out.push_back(r.info);
  return out;
}

void install_routes(httplib::Server& server, App& app) {
  for (const auto& [info, handler] : route_table()) {
    const std::string pattern = pattern_of(info.path);
    auto guarded_handler = guarded(app, handler, info.needs_token);
    if (info.method == "GET") server.Get(pattern, guarded_handler);
    if (info.method == "POST") server.Post(pattern, reading(app, handler, info.needs_token));
    if (info.method == "DELETE") server.Delete(pattern, guarded_handler);
  }
}

}  // namespace stoss::server::http
