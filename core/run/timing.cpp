#include "core/run/timing.hpp"

#include <sys/resource.h>

namespace stoss::run {

double peak_resident_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return double(usage.ru_maxrss) * 1024.0;
}

}  // namespace stoss::run
