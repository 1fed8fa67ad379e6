#include "core/run/timing.hpp"

#include <sys/resource.h>

#include <fstream>
#include <string>

#include "core/model/observer.hpp"
#include "core/parallel/element_share.hpp"
#include "core/run/problem.hpp"
#include "core/time/integrator.hpp"

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

void add_timing(model::Summary& sum, const time::Integrator& integrator, const Problem& problem,
                double wall_seconds, double output_seconds) {
  sum.wall_seconds = wall_seconds;
  sum.linear_factorization_seconds = integrator.linear_factorization_seconds();
  sum.linear_solve_seconds = integrator.linear_solve_seconds();
  sum.linear_solver_seconds = sum.linear_factorization_seconds + sum.linear_solve_seconds;
  sum.assembly_seconds = problem.setup_seconds + integrator.inertia_seconds();
  sum.contact_seconds = problem.setup_contact_seconds;
  const size_t terms = problem.terms().size();
  for (size_t k = 0; k < terms; ++k)
    (k < problem.first_contact_term() ? sum.assembly_seconds : sum.contact_seconds) +=
        integrator.term_seconds(k);
  sum.output_seconds = output_seconds;
  sum.peak_memory_bytes = parallel::total_over_ranks(peak_resident_bytes());  // every rank's
}

}  // namespace stoss::run
