// The worker threads of the terms' loops (core/parallel/worker_threads.hpp) shall run every item of a range
// exactly once, on as many threads as asked, reuse their threads from one call to the next, and take their
// count from set_worker_threads when it is set.
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "core/parallel/worker_threads.hpp"

namespace stoss::parallel {
namespace {

TEST(WorkerThreads, RunEveryItemOnceOnAsManyThreadsAsAsked) {
  WorkerThreads pool;
  for (int threads : {1, 2, 3, 5}) {
    for (int round = 0; round < 3; ++round) {  // the same workers, called again
      std::vector<std::atomic<int>> seen(101);
      for (std::atomic<int>& count : seen) count = 0;
      std::mutex mutex;
      std::set<std::thread::id> ids;
      pool.for_each(0, 101, threads, 1, [&](int i) {
        seen[i]++;
        std::lock_guard lock(mutex);
        ids.insert(std::this_thread::get_id());
      });
      for (int i = 0; i < 101; ++i) EXPECT_EQ(seen[i], 1) << "item " << i << ", " << threads << " threads";
      EXPECT_EQ(static_cast<int>(ids.size()), threads);
    }
  }
}

TEST(WorkerThreads, FewerItemsThanTheSmallestRangeRunOnTheCallingThread) {
  WorkerThreads pool;
  std::set<std::thread::id> ids;
  pool.for_each(10, 25, 4, 16, [&](int) { ids.insert(std::this_thread::get_id()); });
  ASSERT_EQ(ids.size(), 1u);
  EXPECT_EQ(*ids.begin(), std::this_thread::get_id());
}

TEST(WorkerThreads, SetWorkerThreadsOverridesAndZeroRestoresTheDefault) {
  const int default_threads = worker_threads();
  EXPECT_GE(default_threads, 1);
  set_worker_threads(3);
  EXPECT_EQ(worker_threads(), 3);
  set_worker_threads(0);
  EXPECT_EQ(worker_threads(), default_threads);
}

}  // namespace
}  // namespace stoss::parallel
