#include "core/contact/penalty/penalty_term.hpp"

#include <algorithm>
#include <cmath>

#include "core/contact/geometry/assignment.hpp"
#include "core/contact/geometry/face_switch.hpp"
#include "core/contact/geometry/local_patch.hpp"
#include "core/contact/penalty/patch_penalty_element.hpp"

namespace stoss::contact {
namespace {

PenaltyParameters parameters_of(const model::ContactPair& pair, double default_stiffness) {
  PenaltyParameters p;
  p.normal_stiffness = pair.normal_stiffness.value_or(default_stiffness);  // §5.1 [choice]
  // μ = 0: no tangential spring, so the element never runs the return map (5.3).
  p.tangential_stiffness = pair.friction > 0 ? pair.tangential_stiffness.value_or(default_stiffness) : 0.0;
  p.friction = pair.friction;
  p.normal_rule = pair.normal_traction == model::NormalTraction::midpoint ? NormalRule::midpoint
                                                                          : NormalRule::discrete_derivative;
  return p;
}

bool same_structure(const std::vector<PenaltyContact>& a, const std::vector<PenaltyContact>& b) {
  if (a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); ++k)
    if (a[k].slave != b[k].slave || a[k].face != b[k].face) return false;
  return true;
}

}  // namespace

PenaltyContactTerm::PenaltyContactTerm(const mesh::Mesh& mesh, const model::ContactPair& pair,
                                       double master_youngs_modulus, bool static_steps)
    : ContactTerm(mesh, pair) {
  params_ = parameters_of(pair, penalty_default_stiffness(master_youngs_modulus, surfaces_.mean_face_size));
  params_.at_end = static_steps;
  committed_.assign(surfaces_.slave_nodes.size(), PenaltyNodeState{});
  for (const TensorPatch& patch : surfaces_.patches) local_patches_.push_back(local_patch(patch));
}

template <class Use>
void PenaltyContactTerm::evaluate(const PenaltyContact& c, const Eigen::VectorXd& x_n,
                                  const Eigen::VectorXd& x_1, Use&& use) const {
  const int node = surfaces_.slave_nodes[c.slave];
  PenaltyParameters p = params_;
  p.gap_offset = c.gap_offset;
  const auto counted = [&](const auto& r) {
    if (r.closed && params_.tangential_stiffness > 0) ++return_maps_;
    use(r);
  };
  if (surfaces_.smooth()) {
    const TensorPatch& patch = surfaces_.patches[c.face];
    counted(patch_penalty_element(local_patches_[c.face], local_positions(node, patch, x_n),
                                  local_positions(node, patch, x_1), c.history, p, c.xi_n,
                                  surfaces_.face_size[c.face]));  // §5.2 on the patch
  } else {
    const mesh::Quad& face = surfaces_.faces[c.face];
    counted(penalty_element(element_positions(node, face, x_n), element_positions(node, face, x_1), c.history,
                            p,
                            c.xi_n));  // §5.2
  }
}

int PenaltyContactTerm::face_for(int slave, const time::StepContext& step, Eigen::Vector2d& xi) const {
  const PenaltyNodeState& last = committed_[slave];
  if (last.face >= 0 && !leaves_face(last.xi, pair_.switch_hysteresis)) {  // §3.4 (face_switch.hpp)
    xi = last.xi;
    return last.face;
  }
  const Eigen::Vector3d x_s = step.x_n.segment<3>(3 * surfaces_.slave_nodes[slave]);
  const FaceProjection best = best_face(x_s, broad_.candidates(slave), surfaces_, step.x_n, last.face);
  if (best.found()) {
    xi = best.projection.xi;
    return best.face;
  }
  xi = last.xi;  // none accepts x_n: stay on the (consistently extended) face, if any
  return last.face;
}

void PenaltyContactTerm::prepare_step(const time::StepContext& step) {
  if (!announced_) {
    announced_ = true;
    log(step,
        "penalty ε_N = " + scientific(params_.normal_stiffness) +
            (params_.friction > 0 ? ", ε_T = " + scientific(params_.tangential_stiffness) +
                                        ", Coulomb μ = " + scientific(params_.friction)
                                  : ", frictionless (μ = 0): no tangential traction, no return mapping"));
  }
  broad_.update(surfaces_, step.x_n, step.x_n + step.force_factor * step.v_n);
  std::vector<PenaltyContact> next;
  switches_ = 0;
  switch_jump_ = 0;
  for (int i : broad_.near_slaves()) {
    PenaltyContact c;
    c.slave = i;
    c.face = face_for(i, step, c.xi_n);
    if (c.face < 0) continue;
    c.dofs = element_dofs(surfaces_.slave_nodes[i], surfaces_, c.face);
    c.history = committed_[i].history;  // spatial t_{T,n}: carried across a face switch (§5.2 item 3)
    c.gap_offset = committed_[i].gap_offset;
    if (committed_[i].face >= 0 && c.face != committed_[i].face)
      c.gap_offset = switch_face(i, c.face, step.x_n);
    next.push_back(c);
  }
  if (same_structure(next, contacts_)) {
    for (size_t k = 0; k < next.size(); ++k) next[k].block = contacts_[k].block;
  } else {
    ++generation_;
  }
  contacts_ = std::move(next);
}

double PenaltyContactTerm::switch_face(int slave, int face, const Eigen::VectorXd& x_n) {
  const Eigen::Vector3d x_s = x_n.segment<3>(3 * surfaces_.slave_nodes[slave]);
  const PenaltyNodeState& last = committed_[slave];
  const Projection before = project_on(x_s, last.face, surfaces_, x_n, last.xi).projection;
  const Projection after = project_on(x_s, face, surfaces_, x_n).projection;
  ++switches_;
  if (!(before.converged && after.converged)) return 0;
  const double kept = before.gap - last.gap_offset;  // the gap W_N(x_n) was measured with (5.1)
  const double offset = switched_gap_offset(pair_.switch_gap, kept, after.gap);  // §3.4 (face_switch.hpp)
  switch_jump_ += normal_penalty_energy(params_.normal_stiffness, after.gap - offset) -
                  normal_penalty_energy(params_.normal_stiffness, kept);
  return offset;
}

void PenaltyContactTerm::register_pair_blocks(solve::BlockPattern& pattern) {
  for (PenaltyContact& c : contacts_) c.block = pattern.add_block(c.dofs);  // non-symmetric values
}

void PenaltyContactTerm::add_pair(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                                  solve::BlockPattern* K) const {
  for (const PenaltyContact& c : contacts_) {
    if (!computes(c.slave)) continue;
    evaluate(c, step.x_n, z, [&](const auto& r) {
      if (!r.closed) return;
      for (size_t i = 0; i < c.dofs.size(); ++i) R[c.dofs[i]] += step.force_factor * r.force[i];  // h·(5.2)
      if (K) K->scatter(c.block, step.force_factor * r.tangent);
    });
  }
}

void PenaltyContactTerm::end_step(const time::StepContext& step, const Eigen::VectorXd& z) {
  report_ = ContactReport{};
  const Eigen::VectorXd x = z.head(step.x_n.size());
  std::vector<PenaltyNodeState> next(surfaces_.slave_nodes.size());
  clear_pressure();
  last_slip_work_ = 0;
  for (const PenaltyContact& c : contacts_)
    evaluate(c, step.x_n, x, [&](const auto& r) {
      PenaltyNodeState& node = next[c.slave];
      node.face = c.face;
      node.xi = r.at_1.converged ? r.at_1.xi : c.xi_n;
      node.history = r.history_after;  // committed only now; reset when the contact opened (§5.2 item 7)
      const bool clear = r.at_1.converged && r.at_1.gap >= 0 && r.at_1.gap - c.gap_offset >= 0;
      node.gap_offset = clear ? 0.0 : c.gap_offset;  // W_N = 0 with or without it: clearing changes nothing
      if (r.at_1.converged)
        report_.max_own_face_penetration = std::max(report_.max_own_face_penetration, -r.at_1.gap);
      if (!r.closed) return;
      ++report_.active;
      report_.slipping += r.slip;
      last_slip_work_ += r.slip_work;             // D += t_{n+1}·Δξ_p (§5.2 item 7)
      add_pressure(c.slave, -r.normal_traction);  // t_N ≤ 0 (5.1)
    });
  measure_closest_penetration(step, x);
  report_.switches = switches_;
  report_.energy_jump = switch_jump_;
  committed_ = std::move(next);
  dissipated_ += last_slip_work_;
}

double PenaltyContactTerm::energy(const Eigen::VectorXd& x) const {
  double W = 0;
  if (params_.tangential_stiffness > 0)
    for (const PenaltyNodeState& node : committed_)
      W += node.history.traction.squaredNorm() / (2 * params_.tangential_stiffness);  // W_T (5.1)
  BroadPhase near;
  near.update(surfaces_, x, x);
  for (int i : near.near_slaves()) {
    const Eigen::Vector3d x_s = x.segment<3>(3 * surfaces_.slave_nodes[i]);
    const PenaltyNodeState& node = committed_[i];
    const FaceProjection p = node.face >= 0 ? project_on(x_s, node.face, surfaces_, x, node.xi)
                                            : best_face(x_s, near.candidates(i), surfaces_, x);
    const double offset = node.face >= 0 ? node.gap_offset : 0.0;
    if (p.found() && p.projection.converged)
      W += normal_penalty_energy(params_.normal_stiffness, p.projection.gap - offset);  // W_N (5.1)
  }
  return W;
}

}  // namespace stoss::contact
