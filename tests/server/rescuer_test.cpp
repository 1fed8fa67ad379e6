// The rescuer, on a fake clock: the system shall requeue a job whose worker stopped renewing its lease,
// up to a bounded number of attempts, then fail it with the reason.
#include "server/jobs/rescuer.hpp"

#include <gtest/gtest.h>

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
  store.claim("w", lease);
  clock.advance(lease - 1);
  EXPECT_EQ(rescuer.run_once().total(), 0);
  EXPECT_EQ(store.get(id)->status, Status::running);
}

TEST_P(RescuerTest, RenewedLeasesSurvivePastTheFirstExpiry) {
  const JobId id = queue_one();
  store.claim("w", lease);
  for (int i = 0; i < 10; ++i) {
    clock.advance(lease / 2);
    ASSERT_EQ(store.renew(id, "w", lease), Lease::held);
    EXPECT_EQ(rescuer.run_once().total(), 0);
  }
  EXPECT_EQ(store.get(id)->status, Status::running);
}

TEST_P(RescuerTest, RequeuesAJobWhoseLeaseExpired) {
  const JobId id = queue_one();
  store.claim("dead worker", lease);
  store.progress(id, "dead worker", {7, 30, 0.07, 0.3, 2.0});
  clock.advance(lease + 1);
  const Rescued r = rescuer.run_once();
  EXPECT_EQ(r.requeued, 1);
  const Job job = *store.get(id);
  EXPECT_EQ(job.status, Status::queued);
  EXPECT_EQ(job.progress.step, 0);
  EXPECT_FALSE(job.worker);
  // The dead worker cannot report any more; a new claim is attempt 2.
  EXPECT_FALSE(store.finish(id, "dead worker", {Status::succeeded, std::nullopt, std::nullopt}));
  EXPECT_EQ(store.renew(id, "dead worker", lease), Lease::lost);
  const Job again = *store.claim("new worker", lease);
  EXPECT_EQ(again.id, id);
  EXPECT_EQ(again.attempt, 2);
}

TEST_P(RescuerTest, FailsAJobWithTheReasonAfterMaxAttempts) {
  const JobId id = queue_one();
  for (int attempt = 1; attempt <= 3; ++attempt) {
    ASSERT_EQ(store.claim(std::string("w").append(std::to_string(attempt)), lease)->attempt, attempt);
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
  EXPECT_FALSE(store.claim("w4", lease));
}

TEST_P(RescuerTest, CancelsAnExpiredJobWhoseCancelWasRequested) {
  const JobId id = queue_one();
  store.claim("w", lease);
  store.request_cancel(id);
  clock.advance(lease + 1);
  EXPECT_EQ(rescuer.run_once().canceled, 1);
  EXPECT_EQ(store.get(id)->status, Status::canceled);
}

}  // namespace
}  // namespace stoss::server::jobs
