#include "server/jobs/running/job_protocol.hpp"

#include <fstream>
#include <stdexcept>

#include "core/output/durable_file.hpp"
#include "server/common/json_input.hpp"

namespace stoss::server::jobs {

nlohmann::json job_request_json(const Job& job) {
  return {{"id", job.id.str()},
          {"kind", to_string(job.kind)},
          {"attempt", job.attempt},
          {"worker", job.worker ? nlohmann::json(*job.worker) : nlohmann::json(nullptr)},
          {"scene", job.scene},
          {"study", job.study ? *job.study : nlohmann::json(nullptr)}};
}

Job job_from_request(const nlohmann::json& request) {
  Job job;
  auto id = JobId::parse(request.at("id").get<std::string>());
  if (!id) throw std::invalid_argument("job request: malformed id");
  job.id = *id;
  auto kind = parse_kind(request.at("kind").get<std::string>());
  if (!kind) throw std::invalid_argument("job request: unknown kind");
  job.kind = *kind;
  job.status = Status::running;
  job.attempt = request.value("attempt", 0);
  if (request.contains("worker") && request["worker"].is_string())
    job.worker = request["worker"].get<std::string>();
  job.scene = request.at("scene");
  if (request.contains("study") && !request["study"].is_null()) job.study = request["study"];
  return job;
}

void write_job_request(const std::filesystem::path& attempt_dir, const Job& job) {
  output::write_durably(attempt_dir / job_request_file, safe_dump(job_request_json(job)));
}

Job read_job_request(const std::filesystem::path& attempt_dir) {
  const auto path = attempt_dir / job_request_file;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  return job_from_request(nlohmann::json::parse(std::string(std::istreambuf_iterator<char>(in), {})));
}

std::string progress_line(const Progress& progress) {
  return safe_dump({{"progress", to_json(progress)}}) + "\n";
}

std::optional<Progress> progress_from_line(const std::string& line) {
  try {
    const auto message = nlohmann::json::parse(line);
    if (message.contains("progress")) return progress_from_json(message["progress"]);
  } catch (const std::exception&) {  // a torn line: the next report comes soon
  }
  return std::nullopt;
}

}  // namespace stoss::server::jobs
