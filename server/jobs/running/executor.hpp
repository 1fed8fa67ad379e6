#pragma once
/// @file Executor: where a claimed job runs — the seam between the queue and the computation.
/// The in-process executor (inprocess_executor.hpp) is one; a cluster executor could be another.

#include <atomic>
#include <functional>

#include "server/jobs/job.hpp"
#include "server/jobs/store/store.hpp"

namespace stoss::server::jobs {

/// Receives progress while a job runs (already throttled by the executor).
using ProgressSink = std::function<void(const Progress&)>;

class Executor {
 public:
  virtual ~Executor() = default;
  /// Runs `job` (as returned by JobStore::claim, scene included) to its end and says how it ended:
  /// succeeded with a summary, canceled when `cancel` was set before the last step, or failed with
  /// the reason. Must not throw.
  virtual Outcome run(const Job& job, const std::atomic<bool>& cancel, const ProgressSink& progress) = 0;
};

}  // namespace stoss::server::jobs
