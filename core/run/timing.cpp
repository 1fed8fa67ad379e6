#include "core/run/timing.hpp"

#include <sys/resource.h>

#include <fstream>
#include <string>

namespace stoss::run {

double peak_resident_bytes() {
  // VmHWM is this process's own high-water mark since its exec. getrusage's ru_maxrss is not: Linux
  // keeps it across execve, so a job process spawned by a server reported the server's peak.
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) * 1024.0;  // "VmHWM:  1234 kB"
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return double(usage.ru_maxrss) * 1024.0;
}

}  // namespace stoss::run
