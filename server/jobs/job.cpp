#include "server/jobs/job.hpp"

namespace stoss::server::jobs {

std::string to_string(Status s) {
  switch (s) {
    case Status::queued:
      return "queued";
    case Status::running:
      return "running";
    case Status::succeeded:
      return "succeeded";
    case Status::failed:
      return "failed";
    case Status::canceled:
      return "canceled";
  }
  return "unknown";
}

std::optional<Status> parse_status(std::string_view text) {
  for (Status s : all_statuses)
    if (to_string(s) == text) return s;
  return std::nullopt;
}

bool is_terminal(Status s) {
  return s == Status::succeeded || s == Status::failed || s == Status::canceled;
}

std::string to_string(Kind k) {
  return k == Kind::study ? "study" : "simulation";
}

std::optional<Kind> parse_kind(std::string_view text) {
  if (text == "simulation") return Kind::simulation;
  if (text == "study") return Kind::study;
  return std::nullopt;
}

nlohmann::json to_json(const Progress& p) {
  return {{"step", p.step},
          {"steps", p.steps},
          {"time", p.time},
          {"end", p.end},
          {"eta_seconds", p.eta_seconds ? nlohmann::json(*p.eta_seconds) : nlohmann::json(nullptr)}};
}

Progress progress_from_json(const nlohmann::json& j) {
  Progress p;
  if (!j.is_object()) return p;
  p.step = j.value("step", 0);
  p.steps = j.value("steps", 0);
  p.time = j.value("time", 0.0);
  p.end = j.value("end", 0.0);
  if (j.contains("eta_seconds") && j["eta_seconds"].is_number())
    p.eta_seconds = j["eta_seconds"].get<double>();
  return p;
}

}  // namespace stoss::server::jobs
