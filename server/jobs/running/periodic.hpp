#pragma once
/// @file Periodic: a background thread that calls a task at a fixed interval until stopped.

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace stoss::server::jobs {

class Periodic {
 public:
  /// Starts a thread that calls `task` every `interval` (first call after one interval).
  /// Exceptions from `task` are reported on stderr and do not stop the loop.
  Periodic(std::string name, std::chrono::milliseconds interval, std::function<void()> task);
  ~Periodic() { stop(); }
  Periodic(const Periodic&) = delete;
  Periodic& operator=(const Periodic&) = delete;

  /// Wakes the thread and joins it; the task is not called again.
  void stop();

 private:
  void loop();

  std::string name_;
  std::chrono::milliseconds interval_;
  std::function<void()> task_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace stoss::server::jobs
