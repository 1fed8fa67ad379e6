#include "core/contact/lagrange/elements/midpoint_term.hpp"

#include <algorithm>
#include <cmath>

#include "core/contact/lagrange/elements/midpoint_element.hpp"

namespace stoss::contact {

MidpointContactTerm::MidpointContactTerm(const mesh::Mesh& mesh, const model::ContactPair& pair)
    : LagrangeContactTerm(mesh, pair) {
  for (const TensorPatch& patch : surfaces_.patches) local_patches_.push_back(local_patch(patch));
}

void MidpointContactTerm::scatter_patch(const ContactElement& e, int offset, const PatchNtsResult& r,
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

void MidpointContactTerm::add(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                              solve::BlockPattern* K) const {
  if (surfaces_.smooth()) {
    for (size_t k = 0; k < elements_.size(); ++k) {
      const ContactElement& e = elements_[k];
      const int o = element_offset(static_cast<int>(k));
      const TensorPatch& patch = surfaces_.patches[e.face];
      const PatchNtsResult r =
          patch_midpoint_element(local_patch_of(e.face), local_positions(slave_node(e), patch, step.x_n),
                                 local_positions(slave_node(e), patch, z), z[o], e.f3, step.force_factor, e.xi);  // (4.2)
      scatter_patch(e, o, r, R, K);
    }
    return;
  }
  for (size_t k = 0; k < elements_.size(); ++k) {
    const ContactElement& e = elements_[k];
    const int o = element_offset(static_cast<int>(k));
    const Vector15 x_n = element_positions(slave_node(e), face_of(e), step.x_n);
    const Vector15 x_1 = element_positions(slave_node(e), face_of(e), z);
    scatter(e, o, midpoint_element(x_n, x_1, z[o], e.f3, step.force_factor, e.xi), R, K);  // (4.2)
  }
}

double MidpointContactTerm::auxiliary_residual_measure(const Eigen::VectorXd& R,
                                                       const time::MeasureScales&) const {
  double worst = 0;
  for (size_t k = 0; k < elements_.size(); ++k)
    worst = std::max(worst, std::abs(R[element_offset(static_cast<int>(k))]) / face_size(elements_[k]));
  return worst;
}

void MidpointContactTerm::write_auxiliaries(const ContactElement& e, const Eigen::VectorXd&, int o,
                                            Eigen::VectorXd& z) const {
  z[o] = e.lambda[0];
}

void MidpointContactTerm::read_auxiliaries(ContactElement& e, const Eigen::VectorXd& z, int o) const {
  e.lambda[0] = z[o];
  const FaceProjection p = project_on(position(e, z), e.face, surfaces(), z, e.xi);
  if (!p.projection.converged) return;
  e.xi = p.projection.xi;  // where the node is at t_{n+1}: next step's start and switch test
  e.d = p.projection.frame.normal;
}

Vector6 MidpointContactTerm::start_residual(const ContactElement& e, const Eigen::VectorXd& x_n) const {
  const FaceProjection p = project_on(position(e, x_n), e.face, surfaces(), x_n, e.xi_n);
  Vector6 g = Vector6::Zero();
  g[0] = p.projection.gap - e.f3;
  return g;
}

}  // namespace stoss::contact
