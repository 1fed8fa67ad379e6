#include "core/run/measured_contact.hpp"

namespace stoss::run {

void MeasuredContact::end_step(const time::StepContext& step, const Eigen::VectorXd& z) {
  Eigen::VectorXd R = Eigen::VectorXd::Zero(z.size());
  pair_.add(step, z, R, nullptr);  // force_factor · f_alg in the position rows (term.hpp)
  force_.setZero();
  for (int node : pair_.surfaces().slave_nodes) force_ -= R.segment<3>(3 * node);
  if (step.force_factor != 0) force_ /= step.force_factor;  // (5b.12)
  pair_.end_step(step, z);
}

}  // namespace stoss::run
