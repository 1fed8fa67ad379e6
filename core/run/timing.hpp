#pragma once
/// @file Wall time and memory of a run, for its summary (model::Summary, docs/api.md).

#include <chrono>

namespace stoss::run {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Peak resident set of this process so far, in bytes: /proc/self/status VmHWM (since exec), else
/// getrusage ru_maxrss (which Linux carries across exec from the spawning process).
double peak_resident_bytes();

}  // namespace stoss::run
