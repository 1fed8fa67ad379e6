#include "server/common/stop_signals.hpp"

#include <signal.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>

namespace stoss::server {
namespace {

std::atomic<pid_t> waiting_thread{0};  ///< kernel thread id, 0: none

extern "C" void pass_on_to_waiting_thread(int signal) {
  const pid_t thread = waiting_thread.load();
  if (thread != 0) syscall(SYS_tgkill, getpid(), thread, signal);  // async-signal-safe, unlike pthread_kill
}

}  // namespace

StopSignalRoute::StopSignalRoute() {
  waiting_thread = gettid();
  struct sigaction action {};
  action.sa_handler = pass_on_to_waiting_thread;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

StopSignalRoute::~StopSignalRoute() { waiting_thread = 0; }

}  // namespace stoss::server
