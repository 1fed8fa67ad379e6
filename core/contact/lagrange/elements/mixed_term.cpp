#include "core/contact/lagrange/elements/mixed_term.hpp"

#include <algorithm>

#include "core/contact/lagrange/elements/mixed_element.hpp"
#include "core/contact/lagrange/elements/patch_mixed_element.hpp"

namespace stoss::contact {

Vector20 MixedContactTerm::coordinates(const ContactElement& e, const Eigen::VectorXd& x,
                                       const Eigen::Vector3d& d, const Eigen::Vector2d& xi) const {
  return mixed_coordinates(position(e, x), face_positions(face_of(e), x), d, xi);
}

PatchMixedState MixedContactTerm::patch_state(const ContactElement& e, const Eigen::VectorXd& x,
                                              const Eigen::Vector3d& d, const Eigen::Vector2d& xi) const {
  const TensorPatch& patch = surfaces_.patches[e.face];
  PatchMixedState s{position(e, x), Eigen::MatrixXd(patch.size(), 3), d, xi};
  for (int K = 0; K < patch.size(); ++K) s.master.row(K) = x.segment<3>(3 * patch.nodes[K]).transpose();
  return s;
}

void MixedContactTerm::add_smooth(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                                  solve::BlockPattern* K) const {
  for (size_t k = 0; k < elements_.size(); ++k) {
    const ContactElement& e = elements_[k];
    if (!computes(e.slave)) continue;
    const int o = element_offset(static_cast<int>(k));
    const PatchMixedResult r = patch_mixed_element(
        surfaces_.patches[e.face], patch_state(e, step.x_n, e.d_n, e.xi_n),
        patch_state(e, z, z.segment<3>(o), z.segment<2>(o + 3)), z.segment<6>(o + 5), e.f3,
        step.force_factor);  // docs/smooth_master_surface.md (3.5)
    const std::vector<int> dofs = element_dofs(slave_node(e), surfaces_, e.face);
    const int n = static_cast<int>(dofs.size());
    for (int i = 0; i < n; ++i) R[dofs[i]] += r.Rq[i];
    R.segment<5>(o) += r.Rq.segment<5>(n);
    R.segment<6>(o + 5) += r.Rl;
    if (K) K->scatter(e.block, r.K);  // rows: dofs, then d, ξ, λ (register_blocks)
  }
}

void MixedContactTerm::add_pair(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                                solve::BlockPattern* K) const {
  if (surfaces_.smooth()) return add_smooth(step, z, R, K);
  Eigen::Matrix<double, 26, 26> block;
  for (size_t k = 0; k < elements_.size(); ++k) {
    const ContactElement& e = elements_[k];
    if (!computes(e.slave)) continue;
    const int o = element_offset(static_cast<int>(k));
    const Vector20 q_n = coordinates(e, step.x_n, e.d_n, e.xi_n);
    const Vector20 q_1 = coordinates(e, z, z.segment<3>(o), z.segment<2>(o + 3));
    const MixedResult r =
        mixed_element(q_n, q_1, z.segment<6>(o + 5), e.f3, step.force_factor);  // (4.9)–(4.10)
    const std::array<int, 15> dofs = element_dofs(slave_node(e), face_of(e));
    for (int i = 0; i < 15; ++i) R[dofs[i]] += r.Rq[i];
    R.segment<5>(o) += r.Rq.tail<5>();
    R.segment<6>(o + 5) += r.Rl;
    if (!K) continue;
    block.setZero();
    block.topLeftCorner<20, 20>() = r.Kqq;
    block.topRightCorner<20, 6>() = r.Kql;
    block.bottomLeftCorner<6, 20>() = r.Klq;
    K->scatter(e.block, block);
  }
}

double MixedContactTerm::auxiliary_residual_measure(const Eigen::VectorXd& R,
                                                    const time::MeasureScales& s) const {
  double worst = 0;
  for (size_t k = 0; k < elements_.size(); ++k) {
    const int o = element_offset(static_cast<int>(k));
    const double l = face_size(elements_[k]);
    const Vector6 g = R.segment<6>(o + 5);
    const Vector6 scaled =
        (Vector6() << g[0] / l, g[1] / l, g[2] / l, g[3], g[4] / (l * l), g[5] / (l * l)).finished();
    worst = std::max({worst, R.segment<5>(o).norm() / (s.momentum * l), scaled.norm()});
  }
  return worst;
}

double MixedContactTerm::auxiliary_increment_measure(const Eigen::VectorXd& dz,
                                                     const time::MeasureScales&) const {
  double worst = 0;
  for (size_t k = 0; k < elements_.size(); ++k)
    worst = std::max(worst, dz.segment<5>(element_offset(k)).norm());
  return worst;
}

void MixedContactTerm::write_auxiliaries(const ContactElement& e, const Eigen::VectorXd& z_x, int o,
                                         Eigen::VectorXd& z) const {
  const FaceProjection p = project_on(position(e, z_x), e.face, surfaces(), z_x, e.xi);
  const bool predicted = p.projection.converged;  // (d, ξ) predictor: CPP at the current iterate (§4.3.7)
  z.segment<3>(o) = predicted ? p.projection.frame.normal : e.d;
  z.segment<2>(o + 3) = predicted ? p.projection.xi : e.xi;
  z.segment<6>(o + 5) = e.lambda;
}

void MixedContactTerm::read_auxiliaries(ContactElement& e, const Eigen::VectorXd& z, int o) const {
  e.d = z.segment<3>(o);
  e.xi = z.segment<2>(o + 3);
  e.lambda = z.segment<6>(o + 5);
}

Vector6 MixedContactTerm::start_residual(const ContactElement& e, const Eigen::VectorXd& x_n) const {
  if (surfaces_.smooth())
    return patch_constraints(surfaces_.patches[e.face], patch_state(e, x_n, e.d_n, e.xi_n), e.f3);  // (4.11)
  return constraints(invariants(coordinates(e, x_n, e.d_n, e.xi_n), e.f3));  // g(π_n) of (4.11)
}

void MixedContactTerm::add_impact_impulse(const time::StepContext& step, const Eigen::VectorXd& z,
                                          Eigen::VectorXd& b, double& energy_jump) const {
  if (impact() != model::ImpactMode::velocity_correction) return;
  for (size_t k = 0; k < elements_.size(); ++k) {
    const ContactElement& e = elements_[k];
    const int o = element_offset(static_cast<int>(k));
    if (!e.jump) continue;
    const Vector6 lambda = z.segment<6>(o + 5);
    energy_jump += lambda.dot(e.g_n);  // ΔH_imp (4.11)
    const Eigen::Vector3d d = z.segment<3>(o);
    const Eigen::Vector2d xi = z.segment<2>(o + 3);
    const std::vector<double> N = surfaces_.smooth()
                                      ? patch_values(surfaces_.patches[e.face], xi[0], xi[1]).N
                                      : patch_values(bilinear_patch(face_of(e)), xi[0], xi[1]).N;
    const std::vector<int> dofs = element_dofs(slave_node(e), surfaces_, e.face);
    for (int i = 0; i < 3; ++i)
      b[dofs[i]] += step.force_factor * lambda[0] * d[i];  // G_s = [d; −N_K d] (4.12)
    for (size_t K = 0; K < N.size(); ++K)
      for (int i = 0; i < 3; ++i) b[dofs[3 + 3 * K + i]] -= step.force_factor * lambda[0] * N[K] * d[i];
  }
}

}  // namespace stoss::contact
