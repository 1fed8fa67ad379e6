#include "server/jobs/running/rescuer.hpp"

namespace stoss::server::jobs {

Rescued Rescuer::run_once() {
  const Millis now = clock_.now();
  int adopted = 0;
  if (files_)
    for (const Claim& claim : store_.expired(now))
      // The expired attempt's own run or an earlier one: published under the expired claim, so a worker
      // that reports it at the same moment, or a rescuer in another process, makes no second change.
      if (auto outcome = files_->completed_before(claim.id, claim.attempt + 1))
        adopted += store_.finish(claim, *outcome) ? 1 : 0;
  Rescued rescued = store_.requeue_expired(now, max_attempts_);
  rescued.adopted = adopted;
  return rescued;
}

}  // namespace stoss::server::jobs
