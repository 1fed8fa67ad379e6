#include "core/contact/lagrange/lagrange_term.hpp"

#include "core/contact/geometry/face_switch.hpp"

#include <algorithm>
#include <cmath>

namespace stoss::contact {
namespace {

/// Activation threshold of §3.5: tol_g = 1e-10 × face size.
constexpr double activation_gap = 1e-10;

}  // namespace

LagrangeContactTerm::LagrangeContactTerm(const mesh::Mesh& mesh, const model::ContactPair& pair)
    : ContactTerm(mesh, pair) {
  element_of_.assign(surfaces_.slave_nodes.size(), -1);
  start_of_ = element_of_;
  toggles_.assign(surfaces_.slave_nodes.size(), 0);
  released_now_.assign(surfaces_.slave_nodes.size(), 0);
}

void LagrangeContactTerm::register_blocks(solve::BlockPattern& pattern) {
  for (size_t k = 0; k < elements_.size(); ++k) {
    ContactElement& e = elements_[k];
    std::vector<int> rows = element_dofs(slave_node(e), surfaces_, e.face);
    for (int a = 0; a < unknowns_per_element(); ++a) rows.push_back(element_offset(static_cast<int>(k)) + a);
    e.block = pattern.add_block(rows);
  }
}

void LagrangeContactTerm::reindex() {
  std::fill(element_of_.begin(), element_of_.end(), -1);
  for (size_t k = 0; k < elements_.size(); ++k) element_of_[elements_[k].slave] = static_cast<int>(k);
}

void LagrangeContactTerm::switch_face_if_needed(ContactElement& e, const time::StepContext& step) {
  if (!leaves_face(e.xi_n, pair_.switch_hysteresis)) return;  // §3.4 (face_switch.hpp)
  const Eigen::Vector3d x_s = position(e, step.x_n);
  const FaceProjection next = best_face(x_s, broad_.candidates(e.slave), surfaces_, step.x_n, e.face);
  if (!next.found()) return;  // no neighbour accepts x_n: stay on the (consistently extended) face
  const Projection& p = next.projection;
  const double f3 = switched_gap_target(pair_.switch_gap, impact(), p.gap, e.f3);
  e.face = next.face;
  e.d_n = e.d = p.frame.normal;
  e.xi_n = e.xi = p.xi;
  e.f3 = f3;
  e.jump = true;
  ++report_.switches;
  ++generation_;
}

void LagrangeContactTerm::prepare_step(const time::StepContext& step) {
  if (in_step_) elements_ = committed_;  // the last step was abandoned: start again from its start
  in_step_ = true;
  broad_.update(surfaces_, step.x_n, step.x_n + step.h * step.v_n);
  std::fill(toggles_.begin(), toggles_.end(), 0);
  report_ = ContactReport{};
  for (ContactElement& e : elements_) {
    e.d_n = e.d;  // converged values of the last step (§4.3.7): never re-projected
    e.xi_n = e.xi;
    e.jump = false;
    switch_face_if_needed(e, step);
    e.g_n = start_residual(e, step.x_n);
  }
  start_ = elements_;
  reindex();
  start_of_ = element_of_;
}

void LagrangeContactTerm::begin_step(const time::StepContext& step, Eigen::VectorXd& z) {
  initialize_auxiliaries(step, z);
}

void LagrangeContactTerm::initialize_auxiliaries(const time::StepContext& step, Eigen::VectorXd& z) {
  const Eigen::VectorXd z_x = z.head(step.x_n.size());
  for (size_t k = 0; k < elements_.size(); ++k)
    write_auxiliaries(elements_[k], z_x, element_offset(static_cast<int>(k)), z);
}

ContactElement LagrangeContactTerm::new_element(int slave, const FaceProjection& at_end,
                                                const time::StepContext& step) const {
  const int k = start_of_[slave];
  if (k >= 0 && start_[k].face == at_end.face) return start_[k];  // active at t_n: restore its start state
  ContactElement e;
  e.slave = slave;
  e.face = at_end.face;
  const FaceProjection at_start = project_on(step.x_n.segment<3>(3 * surfaces_.slave_nodes[slave]), e.face,
                                             surfaces_, step.x_n, at_end.projection.xi);
  e.d_n = at_start.projection.frame.normal;  // (d_n, ξ_n) = CPP of x_n (§4.3.7)
  e.xi_n = at_start.projection.xi;
  e.d = at_end.projection.frame.normal;
  e.xi = at_end.projection.xi;
  e.f3 = impact() == model::ImpactMode::persist ? std::max(at_start.projection.gap, 0.0) : 0.0;  // §4.5 R1
  e.jump = true;
  e.g_n = start_residual(e, step.x_n);
  return e;
}

bool LagrangeContactTerm::release_tensile(const time::StepContext& step, const Eigen::VectorXd& z) {
  std::vector<ContactElement> kept;
  bool changed = false;
  for (size_t k = 0; k < elements_.size(); ++k) {
    ContactElement& e = elements_[k];
    read_auxiliaries(e, z, element_offset(static_cast<int>(k)));
    if (!(e.lambda[0] > 0)) {
      kept.push_back(e);
    } else if (toggles_[e.slave] > 0) {
      kept.push_back(e);  // anti-cycling (§3.5): a second change in this step is refused
      log(step, "slave node " + std::to_string(slave_node(e)) + " kept active with tensile λ_1 = " +
                    scientific(e.lambda[0]) + " (it already changed state in this step)");
    } else {
      ++toggles_[e.slave];
      released_now_[e.slave] = 1;
      ++report_.releases;
      changed = true;
    }
  }
  elements_ = std::move(kept);
  return changed;
}

bool LagrangeContactTerm::activate_penetrating(const time::StepContext& step, const Eigen::VectorXd& z) {
  bool changed = false;
  for (int i : broad_.near_slaves()) {
    if (element_of_[i] >= 0 || released_now_[i]) continue;
    const Eigen::Vector3d x_s = z.segment<3>(3 * surfaces_.slave_nodes[i]);
    const FaceProjection f = best_face(x_s, broad_.candidates(i), surfaces_, z);
    if (!f.found() || !(f.projection.gap < -activation_gap * surfaces_.face_size[f.face])) continue;
    elements_.push_back(new_element(i, f, step));
    ++toggles_[i];
    ++report_.activations;
    changed = true;
  }
  return changed;
}

bool LagrangeContactTerm::update_active_set(const time::StepContext& step, const Eigen::VectorXd& z) {
  std::fill(released_now_.begin(), released_now_.end(), 0);
  bool changed = release_tensile(step, z);
  reindex();
  broad_.refresh(surfaces_, z.head(step.x_n.size()));
  changed = activate_penetrating(step, z) || changed;
  reindex();
  if (changed) ++generation_;
  return changed;
}

void LagrangeContactTerm::end_step(const time::StepContext& step, const Eigen::VectorXd& z) {
  const Eigen::VectorXd x = z.head(step.x_n.size());
  report_.energy_jump = 0;
  pressure_.clear();
  for (size_t k = 0; k < elements_.size(); ++k) {
    ContactElement& e = elements_[k];
    read_auxiliaries(e, z, element_offset(static_cast<int>(k)));
    if (e.jump) report_.energy_jump += e.lambda.dot(e.g_n);  // (4.11); g(π_n) ≈ 0 for the others
    if (e.jump) report_.max_new_gap_target = std::max(report_.max_new_gap_target, e.f3);
    add_pressure(e.slave, std::max(-e.lambda[0], 0.0));  // λ_1 ≤ 0 in compression (§0)
  }
  report_.active = static_cast<int>(elements_.size());
  committed_ = elements_;
  in_step_ = false;
  for (const ContactElement& e : elements_) {  // §3.4: stays at the Newton tolerance
    const FaceProjection own = project_on(position(e, x), e.face, surfaces_, x, e.xi);
    report_.max_own_face_penetration = std::max(report_.max_own_face_penetration, -own.projection.gap);
  }
  measure_closest_penetration(step, x);
}


}  // namespace stoss::contact
