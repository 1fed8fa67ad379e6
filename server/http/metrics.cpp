#include "server/http/metrics.hpp"

#include <sstream>

namespace stoss::server::http {

void Metrics::count_request(int status) {
  std::lock_guard lock(mutex_);
  ++requests_[status];
}

std::string Metrics::render(const std::map<jobs::Status, std::int64_t>& jobs, int running_here) const {
  std::ostringstream out;
  out << "# HELP stoss_http_requests_total HTTP requests answered, by status code.\n"
      << "# TYPE stoss_http_requests_total counter\n";
  {
    std::lock_guard lock(mutex_);
    for (auto [code, n] : requests_)
      out << "stoss_http_requests_total{code=\"" << code << "\"} " << n << '\n';
  }
  out << "# HELP stoss_jobs Jobs in the store, by status.\n# TYPE stoss_jobs gauge\n";
  for (auto [status, n] : jobs)
    out << "stoss_jobs{status=\"" << jobs::to_string(status) << "\"} " << n << '\n';
  const auto queued = jobs.find(jobs::Status::queued);
  out << "# HELP stoss_queue_depth Jobs waiting for a worker.\n# TYPE stoss_queue_depth gauge\n"
      << "stoss_queue_depth " << (queued == jobs.end() ? 0 : queued->second) << '\n'
      << "# HELP stoss_workers_busy Jobs running in this server process.\n# TYPE stoss_workers_busy gauge\n"
      << "stoss_workers_busy " << running_here << '\n';
  return out.str();
}

}  // namespace stoss::server::http
