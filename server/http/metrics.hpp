#pragma once
/// @file Metrics: counters for GET /metrics (Prometheus text exposition format 0.0.4).

#include <cstdint>
#include <map>
#include <mutex>
#include <string>

#include "server/jobs/job.hpp"

namespace stoss::server::http {

class Metrics {
 public:
  /// Counts one answered request by its status code.
  void count_request(int status);
  /// The exposition text: requests by code, jobs by status, queue depth, jobs running in this process.
  std::string render(const std::map<jobs::Status, std::int64_t>& jobs, int running_here) const;

 private:
  mutable std::mutex mutex_;
  std::map<int, std::uint64_t> requests_;
};

}  // namespace stoss::server::http
