#include "core/contact/contact_term.hpp"

#include <cstdio>

namespace stoss::contact {

ContactTerm::ContactTerm(const mesh::Mesh& mesh, const model::ContactPair& pair)
    : pair_(pair), surfaces_(pair_surfaces(mesh, pair.slave, pair.master)) {}

void ContactTerm::contact_pressure(Eigen::VectorXd& p) const {
  for (const auto& [node, value] : pressure_) p[node] = value;
}

void ContactTerm::log(const time::StepContext& step, const std::string& line) const {
  if (step.log && *step.log) (*step.log)(name() + ": " + line);
}

std::string ContactTerm::scientific(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3e", v);
  return buffer;
}

}  // namespace stoss::contact
