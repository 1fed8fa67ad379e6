#include "core/contact/lagrange/elements/nts_term.hpp"

#include <algorithm>
#include <cmath>

#include "core/contact/geometry/patch_projection.hpp"
#include "core/contact/geometry/patch_variations.hpp"
#include "core/contact/lagrange/elements/hht_element.hpp"
#include "core/contact/lagrange/elements/midpoint_element.hpp"

namespace stoss::contact {

NtsContactTerm::NtsContactTerm(const mesh::Mesh& mesh, const model::ContactPair& pair,
                               const time::ForceRule& rule)
    : LagrangeContactTerm(mesh, pair), end_point_(rule.is_end_point()) {
  for (const TensorPatch& patch : surfaces_.patches) local_patches_.push_back(local_patch(patch));
}

void NtsContactTerm::scatter_patch(const ContactElement& e, int offset, const PatchNtsResult& r,
                                   Eigen::VectorXd& R, solve::BlockPattern* K) const {
  const std::vector<int> dofs = element_dofs(slave_node(e), surfaces_, e.face);
  const int n = static_cast<int>(dofs.size());
  for (int i = 0; i < n; ++i) R[dofs[i]] += r.Rx[i];
  R[offset] += r.Rl;
  if (!K) return;
  Eigen::MatrixXd block = Eigen::MatrixXd::Zero(n + 1, n + 1);
  block.topLeftCorner(n, n) = r.Kxx;
  block.topRightCorner(n, 1) = r.Kxl;
  block.bottomLeftCorner(1, n) = r.Klx;
  K->scatter(e.block, block);
}

void NtsContactTerm::add_pair(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                              solve::BlockPattern* K) const {
  if (!end_point_) return add_midpoint(step, z, R, K);
  for (const auto& [slave, dofs, force] : previous_force_) {
    if (!computes(slave)) continue;
    for (size_t i = 0; i < dofs.size(); ++i)
      R[dofs[i]] +=
          step.rule.previous_weight * step.force_factor * force[i];  // h w_n λ_n N_s(x_n) (2.11), (2.12)
  }
  add_end_point(step, z, R, K);
}

void NtsContactTerm::add_midpoint(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                                  solve::BlockPattern* K) const {
  for_each_element([&](const ContactElement& e, int o) {
    if (surfaces_.smooth()) {
      const TensorPatch& patch = surfaces_.patches[e.face];
      const PatchNtsResult r = patch_midpoint_element(
          local_patch_of(e.face), local_positions(slave_node(e), patch, step.x_n),
          local_positions(slave_node(e), patch, z), z[o], e.f3, step.force_factor, e.xi);  // (4.2)
      return scatter_patch(e, o, r, R, K);
    }
    const Vector15 x_n = element_positions(slave_node(e), face_of(e), step.x_n);
    const Vector15 x_1 = element_positions(slave_node(e), face_of(e), z);
    scatter(e, o, midpoint_element(x_n, x_1, z[o], e.f3, step.force_factor, e.xi), R, K);  // (4.2)
  });
}

void NtsContactTerm::add_end_point(const time::StepContext& step, const Eigen::VectorXd& z,
                                   Eigen::VectorXd& R, solve::BlockPattern* K) const {
  for_each_element([&](const ContactElement& e, int o) {
    if (surfaces_.smooth()) {
      const TensorPatch& patch = surfaces_.patches[e.face];
      return scatter_patch(e, o,
                           patch_hht_element(local_patch_of(e.face), local_positions(slave_node(e), patch, z),
                                             z[o], e.f3, step.force_factor, step.rule.weight, e.xi),
                           R, K);  // (2.11)
    }
    const Vector15 x_1 = element_positions(slave_node(e), face_of(e), z);
    scatter(e, o, hht_element(x_1, z[o], e.f3, step.force_factor, step.rule.weight, e.xi), R, K);  // (2.11)
  });
}

void NtsContactTerm::end_step(const time::StepContext& step, const Eigen::VectorXd& z) {
  LagrangeContactTerm::end_step(step, z);  // reads λ_{n+1} and ξ at x_{n+1} into the elements
  previous_force_.clear();
  if (!end_point_) return;
  for (const ContactElement& e : elements_) {
    const std::vector<int> dofs = element_dofs(slave_node(e), surfaces_, e.face);
    if (!surfaces_.smooth()) {
      const Vector15 x = element_positions(slave_node(e), face_of(e), z);
      previous_force_.push_back({e.slave, dofs, hht_element_force(x, e.lambda[0], e.xi)});
      continue;
    }
    const TensorPatch& local = local_patch_of(e.face);
    const Eigen::VectorXd x = local_positions(slave_node(e), surfaces_.patches[e.face], z);
    const Projection p = patch_projection(x.head<3>(), local, x, e.xi);
    previous_force_.push_back({e.slave, dofs,
                               p.converged ? Eigen::VectorXd(e.lambda[0] * patch_gap_gradient(local, x, p.xi))
                                           : Eigen::VectorXd::Zero(dofs.size())});  // λ N_s (3.6)
  }
}

double NtsContactTerm::auxiliary_residual_measure(const Eigen::VectorXd& R,
                                                  const time::MeasureScales&) const {
  double worst = 0;
  for (size_t k = 0; k < elements_.size(); ++k)
    worst = std::max(worst, std::abs(R[element_offset(static_cast<int>(k))]) / face_size(elements_[k]));
  return worst;
}

void NtsContactTerm::write_auxiliaries(const ContactElement& e, const Eigen::VectorXd&, int o,
                                       Eigen::VectorXd& z) const {
  z[o] = e.lambda[0];
}

void NtsContactTerm::read_auxiliaries(ContactElement& e, const Eigen::VectorXd& z, int o) const {
  e.lambda[0] = z[o];
  const FaceProjection p = project_on(position(e, z), e.face, surfaces(), z, e.xi);
  if (!p.projection.converged) return;
  e.xi = p.projection.xi;  // where the node is at t_{n+1}: next step's start and switch test
  e.d = p.projection.frame.normal;
}

Vector6 NtsContactTerm::start_residual(const ContactElement& e, const Eigen::VectorXd& x_n) const {
  const FaceProjection p = project_on(position(e, x_n), e.face, surfaces(), x_n, e.xi_n);
  Vector6 g = Vector6::Zero();
  g[0] = p.projection.gap - e.f3;
  return g;
}

}  // namespace stoss::contact
