#include "core/contact/hht_term.hpp"

#include "core/contact/hht_element.hpp"

namespace stoss::contact {

void HhtContactTerm::add(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                         solve::BlockPattern* K) const {
  for (const auto& [dofs, force] : previous_force_)
    for (int i = 0; i < 15; ++i) R[dofs[i]] -= step.alpha * step.h * force[i];  // −α h λ_n N_s(x_n) (2.11)
  for (size_t k = 0; k < elements_.size(); ++k) {
    const ContactElement& e = elements_[k];
    const int o = element_offset(static_cast<int>(k));
    const Vector15 x_1 = element_positions(slave_node(e), face_of(e), z);
    scatter(e, o, hht_element(x_1, z[o], e.f3, step.h, step.alpha, e.xi), R, K);  // (2.11)
  }
}

void HhtContactTerm::end_step(const time::StepContext& step, const Eigen::VectorXd& z) {
  LagrangeContactTerm::end_step(step, z);  // reads λ_{n+1} and ξ at x_{n+1} into the elements
  previous_force_.clear();
  for (const ContactElement& e : elements_) {
    const Vector15 x = element_positions(slave_node(e), face_of(e), z);
    previous_force_.emplace_back(element_dofs(slave_node(e), face_of(e)), hht_element_force(x, e.lambda[0], e.xi));
  }
}

}  // namespace stoss::contact
