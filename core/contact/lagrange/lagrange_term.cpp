#include "core/contact/lagrange/lagrange_term.hpp"

#include <algorithm>
#include <cmath>

#include "core/contact/geometry/face_switch.hpp"

namespace stoss::contact {
namespace {

/// Activation threshold of §3.5: tol_g = 1e-10 × face size.
constexpr double activation_gap = 1e-10;
/// closes_touching: a gap up to this fraction of the face size counts as touching (static steps).
constexpr double touching_gap = 1e-8;
/// impact located (§4.6.2): an event closer than this fraction of the step to t_n toggles without a cut.
constexpr double least_cut = 1e-3;
/// impact located: events within this fraction of the step after the earliest one share its cut.
constexpr double event_window = 1e-6;

}  // namespace

LagrangeContactTerm::LagrangeContactTerm(const mesh::Mesh& mesh, const model::ContactPair& pair)
    : ContactTerm(mesh, pair) {
  element_of_.assign(surfaces_.slave_nodes.size(), -1);
  start_of_ = element_of_;
  toggles_.assign(surfaces_.slave_nodes.size(), 0);
  released_now_.assign(surfaces_.slave_nodes.size(), 0);
  pending_ = armed_ = released_now_;
}

void LagrangeContactTerm::register_pair_blocks(solve::BlockPattern& pattern) {
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
  cut_ = 1;
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
  if (pair_.closes_touching) activate_touching(step);
}

void LagrangeContactTerm::activate_touching(const time::StepContext& step) {
  bool changed = false;
  for (int i : broad_.near_slaves()) {
    if (element_of_[i] >= 0) continue;
    const Eigen::Vector3d x_s = step.x_n.segment<3>(3 * surfaces_.slave_nodes[i]);
    const FaceProjection f = best_face(x_s, broad_.candidates(i), surfaces_, step.x_n);
    if (!f.found() || !(f.projection.gap <= touching_gap * surfaces_.face_size[f.face])) continue;
    elements_.push_back(new_element(i, f, step));  // released after the pass if in tension (§3.5)
    changed = true;
  }
  if (!changed) return;
  reindex();
  ++generation_;
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
  const bool frozen = impact() == model::ImpactMode::persist || impact() == model::ImpactMode::located;
  e.f3 = frozen ? std::max(at_start.projection.gap, 0.0) : 0.0;  // §4.5 R1, §4.6.2
  e.jump = true;
  e.g_n = start_residual(e, step.x_n);
  return e;
}

bool LagrangeContactTerm::locates(int slave, const time::StepContext& step) const {
  return impact() == model::ImpactMode::located && step.may_cut && !armed_[slave];
}

LocatedEvent LagrangeContactTerm::located(int slave, double t0, double v0, double t1, double v1,
                                          const time::StepContext& step) const {
  if (secant_.slave == slave && secant_.time != t1) {  // secant through the last cut's solve (§4.6.2)
    t0 = secant_.time;
    v0 = secant_.value;
  }
  const double zero = v1 == v0 ? step.h : t1 - v1 * (t1 - t0) / (v1 - v0);  // (4.14), (4.15)
  return {slave, t1, v1, zero / step.h};
}

LocatedEvent LagrangeContactTerm::release_event(const ContactElement& e,
                                                const time::StepContext& step) const {
  const int k = start_of_[e.slave];
  if (k < 0 || start_[k].face != e.face || !(start_[k].lambda[0] < 0)) return {e.slave, 0, 0, 0};
  // λ_1 of a midpoint-type step belongs to its middle, of an end-point step to its end (4.15).
  const double at = step.rule.is_end_point() ? 1.0 : 0.5;
  return located(e.slave, -at * previous_step_, start_[k].lambda[0], at * step.h, e.lambda[0], step);
}

double LagrangeContactTerm::start_gap(int slave, int face, const time::StepContext& step,
                                      const Eigen::Vector2d& xi) const {
  const Eigen::Vector3d x_s = step.x_n.segment<3>(3 * surfaces_.slave_nodes[slave]);
  return project_on(x_s, face, surfaces_, step.x_n, xi).projection.gap;
}

void LagrangeContactTerm::request_cut(const time::StepContext& step) {
  if (events_.empty()) return;
  const LocatedEvent earliest =
      *std::min_element(events_.begin(), events_.end(),
                        [](const LocatedEvent& a, const LocatedEvent& b) { return a.fraction < b.fraction; });
  std::fill(pending_.begin(), pending_.end(), 0);
  for (const LocatedEvent& e : events_)
    if (e.fraction <= earliest.fraction + event_window) pending_[e.slave] = 1;
  pending_time_ = earliest.fraction * step.h;
  cut_ = earliest.fraction;
  secant_ = earliest;
}

bool LagrangeContactTerm::release_tensile(const time::StepContext& step, const Eigen::VectorXd& z) {
  std::vector<ContactElement> kept;
  bool changed = false;
  for (size_t k = 0; k < elements_.size(); ++k) {
    ContactElement& e = elements_[k];
    read_auxiliaries(e, z, element_offset(static_cast<int>(k)));
    const LocatedEvent release =
        e.lambda[0] > 0 && locates(e.slave, step) ? release_event(e, step) : LocatedEvent{e.slave, 0, 0, 0};
    if (!(e.lambda[0] > 0)) {
      kept.push_back(e);
    } else if (release.fraction >= least_cut && release.fraction < 1) {
      kept.push_back(e);  // §4.6.2: the step ends where λ_1 crosses zero; the release follows then
      events_.push_back(release);
    } else if (toggles_[e.slave] >= (step.inertia ? 1 : 2)) {
      // anti-cycling (§3.5): a second change in this step is refused; a static step may take back an
      // activation of its own once
      kept.push_back(e);
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
    if (locates(i, step)) {
      const double g_n = start_gap(i, f.face, step, f.projection.xi);
      const LocatedEvent event = located(i, 0, g_n, step.h, f.projection.gap, step);  // (4.14)
      if (g_n > 0 && event.fraction >= least_cut && event.fraction < 1) {
        events_.push_back(event);
        continue;
      }
    }
    elements_.push_back(new_element(i, f, step));
    ++toggles_[i];
    ++report_.activations;
    changed = true;
  }
  return changed;
}

bool LagrangeContactTerm::update_active_set(const time::StepContext& step, const Eigen::VectorXd& z) {
  std::fill(released_now_.begin(), released_now_.end(), 0);
  events_.clear();
  bool changed = release_tensile(step, z);
  reindex();
  broad_.refresh(surfaces_, z.head(step.x_n.size()));
  changed = activate_penetrating(step, z) || changed;
  reindex();
  request_cut(step);  // §4.6.2: a located event ends the step there; the step is solved again
  if (changed) ++generation_;
  return changed;
}

void LagrangeContactTerm::end_step(const time::StepContext& step, const Eigen::VectorXd& z) {
  const Eigen::VectorXd x = z.head(step.x_n.size());
  report_.energy_jump = 0;
  clear_pressure();
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
  // §4.6.2: the step ended at the located events of pending_: those nodes toggle in the next step.
  const bool at_events = std::abs(pending_time_ - step.h) <= 1e-9 * step.h;
  for (size_t i = 0; i < armed_.size(); ++i) armed_[i] = at_events && pending_[i];
  std::fill(pending_.begin(), pending_.end(), 0);
  previous_step_ = step.h;
  secant_ = LocatedEvent{};
  for (const ContactElement& e : elements_) {  // §3.4: stays at the Newton tolerance
    const FaceProjection own = project_on(position(e, x), e.face, surfaces_, x, e.xi);
    report_.max_own_face_penetration = std::max(report_.max_own_face_penetration, -own.projection.gap);
  }
  measure_closest_penetration(step, x);
}

}  // namespace stoss::contact
