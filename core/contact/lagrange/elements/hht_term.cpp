#include "core/contact/lagrange/elements/hht_term.hpp"

#include "core/contact/lagrange/elements/hht_element.hpp"
#include "core/contact/geometry/patch_projection.hpp"
#include "core/contact/geometry/patch_variations.hpp"

namespace stoss::contact {

void HhtContactTerm::add(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                         solve::BlockPattern* K) const {
  for (const auto& [dofs, force] : previous_force_)
    for (size_t i = 0; i < dofs.size(); ++i)
      R[dofs[i]] += step.rule.previous_weight * step.force_factor * force[i];  // h w_n λ_n N_s(x_n) (2.11), (2.12)
  if (surfaces_.smooth()) {
    for (size_t k = 0; k < elements_.size(); ++k) {
      const ContactElement& e = elements_[k];
      const int o = element_offset(static_cast<int>(k));
      const TensorPatch& patch = surfaces_.patches[e.face];
      scatter_patch(e, o,
                    patch_hht_element(local_patch_of(e.face), local_positions(slave_node(e), patch, z), z[o], e.f3,
                                      step.force_factor, step.rule.weight, e.xi),
                    R, K);  // (2.11)
    }
    return;
  }
  for (size_t k = 0; k < elements_.size(); ++k) {
    const ContactElement& e = elements_[k];
    const int o = element_offset(static_cast<int>(k));
    const Vector15 x_1 = element_positions(slave_node(e), face_of(e), z);
    scatter(e, o, hht_element(x_1, z[o], e.f3, step.force_factor, step.rule.weight, e.xi), R, K);  // (2.11)
  }
}

void HhtContactTerm::end_step(const time::StepContext& step, const Eigen::VectorXd& z) {
  LagrangeContactTerm::end_step(step, z);  // reads λ_{n+1} and ξ at x_{n+1} into the elements
  previous_force_.clear();
  for (const ContactElement& e : elements_) {
    const std::vector<int> dofs = element_dofs(slave_node(e), surfaces_, e.face);
    if (!surfaces_.smooth()) {
      const Vector15 x = element_positions(slave_node(e), face_of(e), z);
      previous_force_.emplace_back(dofs, hht_element_force(x, e.lambda[0], e.xi));
      continue;
    }
    const TensorPatch& local = local_patch_of(e.face);
    const Eigen::VectorXd x = local_positions(slave_node(e), surfaces_.patches[e.face], z);
    const Projection p = patch_projection(x.head<3>(), local, x, e.xi);
    previous_force_.emplace_back(dofs, p.converged ? Eigen::VectorXd(e.lambda[0] * patch_gap_gradient(local, x, p.xi))
                                                   : Eigen::VectorXd::Zero(dofs.size()));  // λ N_s (3.6)
  }
}

}  // namespace stoss::contact
