#pragma once
/// @file Rescuer: requeues running jobs whose worker stopped renewing its lease (crash, kill -9, hang,
/// a database outage longer than the lease), up to a bounded number of attempts; then the job fails with
/// the reason. A rescued attempt whose run had completed (its outcome.json says succeeded, its result is
/// whole) is not rerun: its result is published as the job's.

#include "server/jobs/clock.hpp"
#include "server/jobs/job_files.hpp"
#include "server/jobs/store/store.hpp"

namespace stoss::server::jobs {

class Rescuer {
 public:
  /// `max_attempts`: runs a job may start before an expired lease fails it instead of requeueing it.
  /// `files`: where to look for completed runs to adopt (none: every expired lease is requeued or failed).
  Rescuer(JobStore& store, const Clock& clock, int max_attempts, std::optional<JobFiles> files = std::nullopt)
      : store_(store), clock_(clock), max_attempts_(max_attempts), files_(std::move(files)) {}

  /// One pass over the expired leases at the clock's current time.
  Rescued run_once();

 private:
  JobStore& store_;
  const Clock& clock_;
  int max_attempts_;
  std::optional<JobFiles> files_;
};

}  // namespace stoss::server::jobs
