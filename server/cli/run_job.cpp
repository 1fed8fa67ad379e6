#include "server/cli/run_job.hpp"

#include <cstdio>
#include <optional>

#include "server/jobs/running/job_process.hpp"

namespace stoss::cli {

namespace {

/// The options of the command line, nullopt when it is not one.
std::optional<server::jobs::JobProcessOptions> parse_run_job(const std::vector<std::string>& args) {
  std::string data_dir, id_text;
  std::size_t memory = 0;
  long parent = 0;
  int attempt = 0, ranks = 1;
  std::string launcher;
  bool launched = false;
  try {
    for (std::size_t i = 0; i < args.size(); ++i) {
      const bool has_value = i + 1 < args.size();
      if (args[i] == "--memory" && has_value)
        memory = std::stoull(args[++i]);
      else if (args[i] == "--attempt" && has_value)
        attempt = std::stoi(args[++i]);
      else if (args[i] == "--parent" && has_value)
        parent = std::stol(args[++i]);
      else if (args[i] == "--ranks" && has_value)
        ranks = std::stoi(args[++i]);
      else if (args[i] == "--launcher" && has_value)
        launcher = args[++i];
      else if (args[i] == "--launched")
        launched = true;
      else if (data_dir.empty())
        data_dir = args[i];
      else if (id_text.empty())
        id_text = args[i];
      else
        return std::nullopt;
    }
  } catch (const std::exception&) {
    return std::nullopt;
  }
  const auto id = server::jobs::JobId::parse(id_text);
  if (data_dir.empty() || !id || attempt < 1 || ranks < 1) return std::nullopt;
  return server::jobs::JobProcessOptions{data_dir, *id, attempt, memory, parent, ranks, launcher, launched};
}

}  // namespace

int run_job_command(const std::vector<std::string>& args) {
  const auto options = parse_run_job(args);
  if (!options) {
    std::fprintf(
        stderr,
        "usage: stoss run-job DATA_DIR JOB_ID --attempt N [--memory BYTES] [--parent PID] [--ranks N "
        "--launcher TEMPLATE | --launched] (internal)\n");
    return 2;
  }
  return server::jobs::run_job_process(*options);
}

}  // namespace stoss::cli
