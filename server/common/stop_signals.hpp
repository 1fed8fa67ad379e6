#pragma once
/// @file SIGINT and SIGTERM for the processes that wait for them in one thread with sigwait (`stoss serve`,
/// `stoss worker`): the one signal route of both. StopSignals blocks them in the main thread before it starts
/// any thread, so every thread it starts blocks them too. Threads a library started while it was loaded,
/// before main, do not block them (OpenBLAS's pthread build starts its pool then), and the kernel may hand a
/// process-wide SIGTERM to such a thread: without a handler the process would die (exit 143) instead of
/// stopping cleanly. StopSignalRoute installs a handler that passes the signal on to the waiting thread.

#include <sys/types.h>

#include <atomic>
#include <csignal>
#include <functional>
#include <thread>

namespace stoss::server {

/// While it lives, SIGINT and SIGTERM arriving on a thread that does not block them go to the thread that
/// made it (which blocks them and waits for them with sigwait); once it is gone they are dropped there,
/// as they stay pending unseen in the threads that block them (a second SIGTERM while stopping).
class StopSignalRoute {
 public:
  StopSignalRoute();
  ~StopSignalRoute();
  StopSignalRoute(const StopSignalRoute&) = delete;
  StopSignalRoute& operator=(const StopSignalRoute&) = delete;
};

/// Blocks SIGINT and SIGTERM in this thread and every thread started after (so construct it before any
/// thread) and ignores SIGPIPE; the destructor restores the signal mask. Wait for a stop signal in this
/// thread (wait) or in a thread of its own (on_stop).
class StopSignals {
 public:
  StopSignals();
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  /// Blocks until SIGINT or SIGTERM arrives and returns it.
  int wait();
  /// Starts a thread that waits for SIGINT or SIGTERM and calls `stop` with it (unless stop_waiting came
  /// first).
  void on_stop(std::function<void(int signal)> stop);
  /// Ends the thread of on_stop (call before what its `stop` touches goes away); idempotent.
  void stop_waiting();
  /// True once stop_waiting was called (a `stop` that waits for something may give up).
  bool stopping() const { return done_; }

 private:
  sigset_t signals_{}, previous_{};
  std::atomic<bool> done_{false};
  std::thread thread_;
};

/// "SIGINT" or "SIGTERM".
const char* stop_signal_name(int signal);

}  // namespace stoss::server
