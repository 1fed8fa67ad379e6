#include "server/common/stop_signals.hpp"

#include <pthread.h>
#include <signal.h>
#include <sys/syscall.h>
#include <unistd.h>

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

StopSignalRoute::~StopSignalRoute() {
  waiting_thread = 0;
}

StopSignals::StopSignals() {
  sigemptyset(&signals_);
  sigaddset(&signals_, SIGINT);
  sigaddset(&signals_, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals_, &previous_);
  signal(SIGPIPE, SIG_IGN);
}

StopSignals::~StopSignals() {
  stop_waiting();
  pthread_sigmask(SIG_SETMASK, &previous_, nullptr);
}

int StopSignals::wait() {
  const StopSignalRoute route;  // signals a library's own threads receive come here
  int received = 0;
  sigwait(&signals_, &received);
  return received;
}

void StopSignals::on_stop(std::function<void(int signal)> stop) {
  thread_ = std::thread([this, stop = std::move(stop)] {
    const int received = wait();
    if (!done_) stop(received);
  });
}

void StopSignals::stop_waiting() {
  done_ = true;
  if (!thread_.joinable()) return;
  pthread_kill(thread_.native_handle(), SIGTERM);  // blocked and awaited: wakes sigwait, kills nothing
  thread_.join();
}

const char* stop_signal_name(int signal) {
  return signal == SIGINT ? "SIGINT" : "SIGTERM";
}

}  // namespace stoss::server
