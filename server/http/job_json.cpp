#include "server/http/job_json.hpp"

namespace stoss::server::http {

namespace {

nlohmann::json time_or_null(const std::optional<jobs::Millis>& t) {
  return t ? nlohmann::json(jobs::format_rfc3339(*t)) : nlohmann::json(nullptr);
}

nlohmann::json links(const jobs::Job& job) {
  const std::string self = "/v1/jobs/" + job.id.str();
  nlohmann::json l = {{"self", self}, {"log", self + "/log"}};
  if (!jobs::is_terminal(job.status)) l["cancel"] = self + "/cancel";
  if (job.status == jobs::Status::succeeded && job.kind == jobs::Kind::study) {
    l["study"] = self + "/study";
  } else if (job.status == jobs::Status::succeeded) {
    l["result"] = self + "/result";
    l["result_xdmf"] = self + "/result.xdmf";
    l["result_mesh_xdmf"] = self + "/result_mesh.xdmf";
    l["series"] = self + "/series";
  }
  return l;
}

/// The warnings and choices of POST; the estimated run time as the ETA of a job that has not measured one.
void add_before_run(nlohmann::json& j, const jobs::Job& job, const nlohmann::json& before_run) {
  j["warnings"] = before_run.value("warnings", nlohmann::json::array());
  j["choices"] = before_run.value("choices", nlohmann::json::array());
  const nlohmann::json estimate =
      before_run.value("estimates", nlohmann::json::object()).value("wall_seconds", nlohmann::json());
  if (!job.progress.eta_seconds && job.progress.step == 0 && !jobs::is_terminal(job.status) &&
      estimate.is_number())
    j["progress"]["eta_seconds"] = estimate;
}

}  // namespace

nlohmann::json job_json(const jobs::Job& job, const nlohmann::json& before_run) {
  nlohmann::json j = {{"id", job.id.str()},
                      {"kind", jobs::to_string(job.kind)},
                      {"status", jobs::to_string(job.status)},
                      {"created", jobs::format_rfc3339(job.created)},
                      {"started", time_or_null(job.started)},
                      {"finished", time_or_null(job.finished)},
                      {"attempt", job.attempt},
                      {"ranks", job.ranks},
                      {"cancel_requested", job.cancel_requested},
                      {"progress", jobs::to_json(job.progress)},
                      {"effects", job.effects},
                      {"summary", job.summary ? *job.summary : nlohmann::json(nullptr)},
                      {"links", links(job)}};
  j["name"] = job.name ? nlohmann::json(*job.name) : nlohmann::json(nullptr);
  j["links"]["scene"] = "/v1/jobs/" + job.id.str() + "/scene";
  if (job.error) j["error"] = *job.error;
  if (job.idempotency_key) j["idempotency_key"] = *job.idempotency_key;
  if (job.study) j["study"] = *job.study;
  if (before_run.is_object()) add_before_run(j, job, before_run);
  return j;
}

}  // namespace stoss::server::http
