#pragma once
/// @file Worker threads for the terms' loops over elements and contact face pairs: how many (STOSS_THREADS),
/// and a pool that lives as long as its owner.

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace stoss::parallel {

/// Threads the terms' loops use (the elements of ElasticityTerm::add, the face pairs of the mortar term): the
/// STOSS_THREADS environment variable when it is a positive integer, else every core the machine has (one job
/// alone uses both cores of the CI machine; a service running several jobs at once sets STOSS_THREADS=1 for
/// its workers). Results do not depend on it: each thread computes whole items into buffers and one thread
/// sums them in item order.
int worker_threads();
/// The hardware threads of this machine, at least 1.
int machine_cores();
/// Overrides worker_threads() for this process (0: back to STOSS_THREADS or the cores).
void set_worker_threads(int threads);

/// Worker threads that live as long as their owner (a term, for the run): run() hands them contiguous
/// ranges of items and waits, instead of starting threads at every residual (~50 µs each, ~650 times
/// in the seed's example). Not shared between owners, so two runs in one process never wait on each other.
class WorkerThreads {
 public:
  WorkerThreads() = default;
  ~WorkerThreads();
  WorkerThreads(const WorkerThreads&) = delete;
  WorkerThreads& operator=(const WorkerThreads&) = delete;
  /// Runs body(i) for i in [begin, end) in `parts` contiguous ranges, the first on this thread, part t
  /// from begin + n t / parts on a worker (started on first need). Returns when every range is done.
  void run(int begin, int end, int parts, const std::function<void(int)>& body);
  /// body(i) for i in [begin, end) on up to `threads` threads, each range at least `smallest` items (fewer
  /// items than that: on this thread alone).
  void for_each(int begin, int end, int threads, int smallest, const std::function<void(int)>& body);

 private:
  void work(int part);
  std::vector<std::thread> workers_;  ///< worker k runs part k + 1
  std::mutex mutex_;
  std::condition_variable start_, done_;
  const std::function<void(int)>* body_ = nullptr;
  int begin_ = 0, end_ = 0, parts_ = 0, pending_ = 0;
  long round_ = 0;
  bool stop_ = false;
};

}  // namespace stoss::parallel
