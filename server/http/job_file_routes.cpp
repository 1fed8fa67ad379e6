#include "server/http/job_file_routes.hpp"

#include <filesystem>
#include <optional>
#include <string>

#include "core/output/result_reader.hpp"
#include "core/study/study.hpp"
#include "server/http/route_support.hpp"
#include "server/jobs/reporting/series_recorder.hpp"
#include "server/jobs/running/study_job.hpp"

namespace stoss::server::http {

namespace {

using httplib::Request;
using httplib::Response;

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

}  // namespace

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

void get_result_xdmf(App& app, const Request& req, Response& res) {
  send_xdmf(app, req, res, &jobs::AttemptFiles::xdmf);
}

void get_result_mesh_xdmf(App& app, const Request& req, Response& res) {
  send_xdmf(app, req, res, &jobs::AttemptFiles::xdmf_mesh);
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
  if (format == "csv")
    return res.set_content(jobs::csv_rows_after(output::series_csv(path), since), "text/csv");
  send_json(res, 200, jobs::series_after(output::series_json(path), since));
}

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

}  // namespace stoss::server::http
