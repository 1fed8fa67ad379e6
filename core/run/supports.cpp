#include "core/run/supports.hpp"

namespace stoss::run {

PrescribedMotion::PrescribedMotion(std::vector<PrescribedDof> dofs, std::vector<loads::Amplitude> amplitudes)
    : dofs_(std::move(dofs)), amplitudes_(std::move(amplitudes)) {}

void PrescribedMotion::begin_step(const time::StepContext& step, Eigen::VectorXd& z) {
  for (const PrescribedDof& d : dofs_)  // x = X + a(t) u (docs/theory.md §5b.9)
    z[d.dof] = d.reference + amplitudes_[size_t(d.amplitude)](t_ + step.h) * d.displacement;
}

void PrescribedMotion::take_reaction(const time::StepContext& step, const Eigen::VectorXd& z,
                                     const Eigen::VectorXd& reaction) {
  for (const PrescribedDof& d : dofs_) work_ += reaction[d.dof] * (z[d.dof] - step.x_n[d.dof]);  // (5b.11)
}

void PrescribedMotion::end_step(const time::StepContext& step, const Eigen::VectorXd&) {
  t_ += step.h;
}

time::TermState PrescribedMotion::save_state() const {
  time::TermState state;
  state.reals["time"] = {t_};
  state.reals["work"] = {work_};
  return state;
}

void PrescribedMotion::restore_state(const time::TermState& state, const Eigen::VectorXd&,
                                     const Eigen::VectorXd&) {
  t_ = state.real("time", 1)[0];
  work_ = state.real("work", 1)[0];
}

}  // namespace stoss::run
