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

std::vector<std::unique_ptr<MeasuredContact>> measured_pairs(const Problem& p) {
  std::vector<std::unique_ptr<MeasuredContact>> out;
  for (const auto& pair : p.contact) out.push_back(std::make_unique<MeasuredContact>(*pair));
  return out;
}

std::vector<time::Term*> terms_of(const Problem& p,
                                  const std::vector<std::unique_ptr<MeasuredContact>>& pairs) {
  std::vector<time::Term*> terms = p.terms();
  for (size_t k = 0; k < pairs.size(); ++k) terms[p.first_contact_term() + k] = pairs[k].get();
  return terms;
}

}  // namespace stoss::run
