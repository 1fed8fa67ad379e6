// The rescuer, on a fake clock: the system shall requeue a job whose worker stopped renewing its lease,
// up to a bounded number of attempts, then fail it with the reason; and shall publish, without spending an
// attempt, the run of an expired attempt that completed but could not report it (issue 20).
#include <gtest/gtest.h>

#include <fstream>

#include "server/jobs/running/rescuer.hpp"
#include "tests/server/live_server.hpp"
#include "tests/server/pg_cluster.hpp"

namespace stoss::server::jobs {
namespace {

constexpr Millis lease = 10'000;

/// Every test runs against both stores.
class RescuerTest : public ::testing::TestWithParam<test::Backend> {
 protected:
  ManualClock clock;
  test::StoreUnderTest backing{GetParam(), clock};
  JobStore& store = backing.store();
  Rescuer rescuer{store, clock, 3};

  JobId queue_one() {
    nlohmann::json scene = {{"name", "x"}};
    return store.create({std::nullopt, "hash", scene, {}, {}, Kind::simulation, std::nullopt}, 100).job->id;
  }
};

INSTANTIATE_TEST_SUITE_P(BothStores, RescuerTest,
                         ::testing::Values(test::Backend::sqlite, test::Backend::postgresql),
                         [](const auto& info) { return test::to_string(info.param); });

TEST_P(RescuerTest, LeavesLiveLeasesAlone) {
  const JobId id = queue_one();
  store.claim("w", lease, 1);
  clock.advance(lease - 1);
  EXPECT_EQ(rescuer.run_once().total(), 0);
  EXPECT_EQ(store.get(id)->status, Status::running);
}

TEST_P(RescuerTest, RenewedLeasesSurvivePastTheFirstExpiry) {
  const JobId id = queue_one();
  store.claim("w", lease, 1);
  for (int i = 0; i < 10; ++i) {
    clock.advance(lease / 2);
    ASSERT_EQ(store.renew({id, "w", 1}, lease), Lease::held);
    EXPECT_EQ(rescuer.run_once().total(), 0);
  }
  EXPECT_EQ(store.get(id)->status, Status::running);
}

TEST_P(RescuerTest, RequeuesAJobWhoseLeaseExpired) {
  const JobId id = queue_one();
  store.claim("dead worker", lease, 1);
  store.progress({id, "dead worker", 1}, {7, 30, 0.07, 0.3, 2.0});
  clock.advance(lease + 1);
  const Rescued r = rescuer.run_once();
  EXPECT_EQ(r.requeued, 1);
  const Job job = *store.get(id);
  EXPECT_EQ(job.status, Status::queued);
  EXPECT_EQ(job.progress.step, 0);
  EXPECT_FALSE(job.worker);
  // The dead worker cannot report any more; a new claim is attempt 2.
  EXPECT_FALSE(store.finish({id, "dead worker", 1}, {Status::succeeded, std::nullopt, std::nullopt}));
  EXPECT_EQ(store.renew({id, "dead worker", 1}, lease), Lease::lost);
  const Job again = *store.claim("new worker", lease, 1);
  EXPECT_EQ(again.id, id);
  EXPECT_EQ(again.attempt, 2);
}

TEST_P(RescuerTest, FailsAJobWithTheReasonAfterMaxAttempts) {
  const JobId id = queue_one();
  for (int attempt = 1; attempt <= 3; ++attempt) {
    ASSERT_EQ(store.claim(std::string("w").append(std::to_string(attempt)), lease, 1)->attempt, attempt);
    clock.advance(lease + 1);
    const Rescued r = rescuer.run_once();
    EXPECT_EQ(r.requeued, attempt < 3 ? 1 : 0);
    EXPECT_EQ(r.failed, attempt < 3 ? 0 : 1);
  }
  const Job job = *store.get(id);
  EXPECT_EQ(job.status, Status::failed);
  EXPECT_EQ(*job.error,
            "the worker stopped renewing its lease (process killed or hung) on attempt 3 of 3; not retried");
  EXPECT_EQ(job.finished, clock.now());
  EXPECT_FALSE(store.claim("w4", lease, 1));
}

TEST_P(RescuerTest, CancelsAnExpiredJobWhoseCancelWasRequested) {
  const JobId id = queue_one();
  store.claim("w", lease, 1);
  store.request_cancel(id);
  clock.advance(lease + 1);
  EXPECT_EQ(rescuer.run_once().canceled, 1);
  EXPECT_EQ(store.get(id)->status, Status::canceled);
}

/// The folder of attempt `attempt` as a run leaves it: outcome.json with `status`, and result.h5 when
/// `with_result`.
void leave_run(const JobFiles& files, const JobId& id, int attempt, Status status, bool with_result) {
  const AttemptFiles folder = files.prepare_attempt(id, attempt);
  if (with_result) std::ofstream(folder.result()) << "complete";
  folder.write_outcome({status, nlohmann::json{{"steps", 30}}, std::nullopt});
}

class AdoptingRescuerTest : public RescuerTest {
 protected:
  test::TempDir data;
  JobFiles files{data.path()};
  Rescuer adopting{store, clock, 3, files};
};

INSTANTIATE_TEST_SUITE_P(BothStores, AdoptingRescuerTest,
                         ::testing::Values(test::Backend::sqlite, test::Backend::postgresql),
                         [](const auto& info) { return test::to_string(info.param); });

TEST_P(AdoptingRescuerTest, PublishesAnExpiredAttemptsCompletedRunWithoutSpendingAnAttempt) {
  const JobId id = queue_one();
  store.claim("away", lease, 1);
  leave_run(files, id, 1, Status::succeeded, true);
  clock.advance(lease + 1);
  const Rescued r = adopting.run_once();
  EXPECT_EQ(r.adopted, 1);
  EXPECT_EQ(r.requeued, 0);
  const Job job = *store.get(id);
  EXPECT_EQ(job.status, Status::succeeded);
  EXPECT_EQ(job.attempt, 1);
  EXPECT_EQ(job.result_attempt, 1);
  EXPECT_EQ((*job.summary)["steps"], 30);
  EXPECT_EQ(files.served(job).result(), files.attempt(id, 1).result());
  EXPECT_FALSE(store.finish({id, "away", 1}, {Status::succeeded, std::nullopt, std::nullopt}))
      << "the worker's own late report changes nothing";
}

TEST_P(AdoptingRescuerTest, OnTheLastAttemptACompletedRunSucceedsInsteadOfFailing) {
  const JobId id = queue_one();
  for (int attempt = 1; attempt <= 3; ++attempt) {
    ASSERT_EQ(store.claim("w" + std::to_string(attempt), lease, 1)->attempt, attempt);
    // Attempts 1 and 2 stop mid-run (no outcome; a canceled one), attempt 3 completes.
    if (attempt == 2) leave_run(files, id, 2, Status::canceled, false);
    if (attempt == 3) leave_run(files, id, 3, Status::succeeded, true);
    clock.advance(lease + 1);
    const Rescued r = adopting.run_once();
    EXPECT_EQ(r.requeued, attempt < 3 ? 1 : 0) << attempt;
    EXPECT_EQ(r.adopted, attempt < 3 ? 0 : 1) << attempt;
    EXPECT_EQ(r.failed, 0) << attempt;
  }
  EXPECT_EQ(store.get(id)->status, Status::succeeded);
  EXPECT_EQ(store.get(id)->result_attempt, 3);
}

TEST_P(AdoptingRescuerTest, AnOutcomeWithoutItsResultIsNotAdopted) {
  const JobId id = queue_one();
  store.claim("w", lease, 1);
  leave_run(files, id, 1, Status::succeeded, false);  // result.h5 gone: nothing to serve
  clock.advance(lease + 1);
  const Rescued r = adopting.run_once();
  EXPECT_EQ(r.adopted, 0);
  EXPECT_EQ(r.requeued, 1);
  EXPECT_EQ(store.get(id)->status, Status::queued);
}

}  // namespace
}  // namespace stoss::server::jobs
