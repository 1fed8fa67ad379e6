#include "core/run/step_forces.hpp"

namespace stoss::run {

void StepForces::add(double h, const std::vector<Eigen::Vector3d>& forces) {
  if (impulse_.empty()) impulse_.assign(forces.size(), Eigen::Vector3d::Zero());
  for (size_t k = 0; k < forces.size(); ++k) impulse_[k] += h * forces[k];
  last_ = forces;
  h_ += h;
  ++substeps_;
}

std::vector<Eigen::Vector3d> StepForces::step_forces() const {
  if (substeps_ <= 1) return last_;
  std::vector<Eigen::Vector3d> out = impulse_;
  for (Eigen::Vector3d& f : out) f /= h_;
  return out;
}

}  // namespace stoss::run
