#pragma once
/// @file Rescuer: requeues running jobs whose worker stopped renewing its lease (crash, kill -9, hang),
/// up to a bounded number of attempts; then the job fails with the reason.

#include "server/jobs/clock.hpp"
#include "server/jobs/store.hpp"

namespace stoss::server::jobs {

class Rescuer {
 public:
  /// `max_attempts`: runs a job may start before an expired lease fails it instead of requeueing it.
  Rescuer(JobStore& store, const Clock& clock, int max_attempts)
      : store_(store), clock_(clock), max_attempts_(max_attempts) {}

  /// One pass over the expired leases at the clock's current time.
  Rescued run_once() { return store_.requeue_expired(clock_.now(), max_attempts_); }

 private:
  JobStore& store_;
  const Clock& clock_;
  int max_attempts_;
};

}  // namespace stoss::server::jobs
