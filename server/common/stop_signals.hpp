#pragma once
/// @file SIGINT and SIGTERM for the processes that wait for them in one thread with sigwait (`stoss serve`,
/// `stoss worker`): blocked in the main thread before it starts any thread, so every thread it starts
/// blocks them too. Threads a library started while it was loaded, before main, do not block them
/// (OpenBLAS's pthread build starts its pool then), and the kernel may hand a process-wide SIGTERM to
/// such a thread: without a handler the process would die (exit 143) instead of stopping cleanly.
/// StopSignalRoute installs a handler that passes the signal on to the waiting thread.

#include <sys/types.h>

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

}  // namespace stoss::server
