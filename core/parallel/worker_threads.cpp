#include "core/parallel/worker_threads.hpp"

#include <algorithm>
#include <atomic>
#include <cstdlib>

namespace stoss::parallel {
namespace {

std::atomic<int> threads_override{0};

int threads_from_environment() {
  if (const char* text = std::getenv("STOSS_THREADS")) {
    const int n = std::atoi(text);
    if (n > 0) return n;
  }
  return machine_cores();
}

}  // namespace

int machine_cores() {
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

int worker_threads() {
  static const int from_environment = threads_from_environment();
  const int n = threads_override.load();
  return n > 0 ? n : from_environment;
}

void set_worker_threads(int threads) {
  threads_override.store(std::max(threads, 0));
}

WorkerThreads::~WorkerThreads() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  start_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

void WorkerThreads::for_each(int begin, int end, int threads, int smallest,
                             const std::function<void(int)>& body) {
  const int n = end - begin;
  threads = std::clamp(threads, 1, std::max(1, n / std::max(smallest, 1)));
  if (threads == 1) {
    for (int i = begin; i < end; ++i) body(i);
    return;
  }
  run(begin, end, threads, body);
}

void WorkerThreads::run(int begin, int end, int parts, const std::function<void(int)>& body) {
  std::unique_lock lock(mutex_);
  while (static_cast<int>(workers_.size()) < parts - 1) {
    const int part = static_cast<int>(workers_.size()) + 1;
    workers_.emplace_back([this, part] { work(part); });
  }
  body_ = &body;
  begin_ = begin;
  end_ = end;
  parts_ = parts;
  pending_ = parts - 1;
  ++round_;
  lock.unlock();
  start_.notify_all();
  const int n = end - begin;
  for (int i = begin; i < begin + n / parts; ++i) body(i);
  lock.lock();
  done_.wait(lock, [this] { return pending_ == 0; });
}

void WorkerThreads::work(int part) {
  long seen = 0;
  std::unique_lock lock(mutex_);
  for (;;) {
    start_.wait(lock, [&] { return stop_ || round_ != seen; });
    if (stop_) return;
    seen = round_;
    if (part >= parts_) continue;
    const int begin = begin_, n = end_ - begin_, parts = parts_;
    const std::function<void(int)>& body = *body_;
    lock.unlock();
    for (int i = begin + n * part / parts; i < begin + n * (part + 1) / parts; ++i) body(i);
    lock.lock();
    if (--pending_ == 0) done_.notify_one();
  }
}

}  // namespace stoss::parallel
