#pragma once
/// @file Wall time and memory of a run, for its summary (model::Summary, docs/api.md).

#include <chrono>

namespace stoss::model {
struct Summary;
}
namespace stoss::time {
class Integrator;
}

namespace stoss::run {

struct Problem;

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Peak resident set of this process so far, in bytes: /proc/self/status VmHWM (since exec), else
/// getrusage ru_maxrss (which Linux carries across exec from the spawning process).
double peak_resident_bytes();

/// Where the wall time went (model::Summary): terms in integrator order, elasticity, loads and gravity as
/// assembly, the contact pairs as contact; the wall time, the output's share and the peak memory.
void add_timing(model::Summary& summary, const time::Integrator& integrator, const Problem& problem,
                double wall_seconds, double output_seconds);

}  // namespace stoss::run
