#include "core/run/measures.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace stoss::run {

Balance balance(const Problem& p, const time::State& s) {
  Balance b;
  const Eigen::VectorXd momentum = p.mass * s.v;
  b.kinetic = 0.5 * s.v.dot(momentum);
  b.strain = p.elasticity->energy(s.x);
  if (p.gravity) b.potential = p.gravity->energy(s.x);
  b.external_work = p.external_work();
  for (const auto& term : p.contact) {
    b.contact += term->energy(s.x);
    b.dissipated += term->dissipated_energy();
  }
  for (Eigen::Index I = 0; I < s.x.size() / 3; ++I) {
    const Eigen::Vector3d pI = momentum.segment<3>(3 * I), xI = s.x.segment<3>(3 * I);
    b.linear += pI;
    b.angular += xI.cross(pI);
    b.momentum_scale += pI.norm();
    b.angular_scale += xI.norm() * pI.norm();
  }
  return b;
}

ContactRow contact_row(const Problem& p, const time::Integrator* integrator) {
  ContactRow c;
  for (const auto& term : p.contact) {
    const contact::ContactReport& r = term->report();
    c.active += r.active;
    c.max_penetration = std::max(c.max_penetration, r.max_penetration);
    c.own_face_penetration = std::max(c.own_face_penetration, r.max_own_face_penetration);
    c.faceted_penetration = std::max(c.faceted_penetration, r.max_faceted_penetration);
    c.energy_jump += r.energy_jump;
    c.switches += r.switches;
    c.unprojected += r.unassigned;
    c.slipping += r.slipping;
  }
  // The velocity correction (4.12) restores (part of) the activation jump as kinetic energy.
  if (integrator) c.energy_jump += integrator->velocity_correction_energy();
  return c;
}

void add_substep(ContactRow& step, const ContactRow& sub) {
  step.active = sub.active;
  step.max_penetration = std::max(step.max_penetration, sub.max_penetration);
  step.own_face_penetration = std::max(step.own_face_penetration, sub.own_face_penetration);
  step.faceted_penetration = std::max(step.faceted_penetration, sub.faceted_penetration);
  step.energy_jump += sub.energy_jump;
  step.switches += sub.switches;
  step.unprojected = std::max(step.unprojected, sub.unprojected);
  step.slipping += sub.slipping;
}

void update_summary(model::Summary& sum, const Balance& b0, const Balance& b, const ContactRow& c) {
  sum.max_abs_energy = std::max({sum.max_abs_energy, std::abs(b.total()), std::abs(b0.total())});
  // H_n − W_n against H_0 (docs/results.md): loaded runs scale by max |H_k| so far, for a start at rest
  const double scale =
      b.external_work != 0 || b0.external_work != 0 ? sum.max_abs_energy : std::abs(b0.total());
  const double H0 = scale > 0 ? scale : 1.0;
  sum.energy_drift = std::max(sum.energy_drift, std::abs(b.total() - b.external_work - b0.total()) / H0);
  sum.external_work = b.external_work;
  const double Ls = std::max(b0.linear.norm(), b0.momentum_scale),
               Js = std::max(b0.angular.norm(), b0.angular_scale);
  if (Ls > 0)
    sum.linear_momentum_drift = std::max(sum.linear_momentum_drift, (b.linear - b0.linear).norm() / Ls);
  if (Js > 0)
    sum.angular_momentum_drift = std::max(sum.angular_momentum_drift, (b.angular - b0.angular).norm() / Js);
  sum.max_penetration = std::max(sum.max_penetration, c.max_penetration);
  sum.max_own_face_penetration = std::max(sum.max_own_face_penetration, c.own_face_penetration);
  sum.max_faceted_penetration = std::max(sum.max_faceted_penetration, c.faceted_penetration);
  // E_n = H_n + D_n − W_n − Σ contact_energy_jump against E_0 (docs/results.md, "Verdict")
  sum.contact_energy_jumps += c.energy_jump;
  const double balance =
      b.total() + b.dissipated - b.external_work - sum.contact_energy_jumps - (b0.total() + b0.dissipated);
  sum.energy_balance_error = std::max(sum.energy_balance_error, std::abs(balance));
  sum.energy_balance_rise = std::max(sum.energy_balance_rise, balance);
}

void update_impulse_balance(model::Summary& sum, const Balance& before, const Balance& after,
                            const StepImpulse& j) {
  const double scale = std::max(
      {before.momentum_scale, after.momentum_scale, j.loads.norm() + j.gravity.norm() + j.supports.norm()});
  if (scale == 0) return;
  const Eigen::Vector3d mismatch = after.linear - before.linear - j.loads - j.gravity - j.supports;  // (V10)
  sum.impulse_balance_error = std::max(sum.impulse_balance_error, mismatch.norm() / scale);
}

}  // namespace stoss::run
