#include "core/run/supports.hpp"

namespace stoss::run {

PrescribedMotion::PrescribedMotion(std::vector<PrescribedDof> dofs, std::vector<loads::Amplitude> amplitudes)
    : dofs_(std::move(dofs)), amplitudes_(std::move(amplitudes)), reaction_n_(dofs_.size(), 0.0) {}

void PrescribedMotion::begin_step(const time::StepContext& step, Eigen::VectorXd& z) {
  for (const PrescribedDof& d : dofs_)  // x = X + a(t) u (docs/theory.md §5b.9)
    z[d.dof] = d.reference + amplitudes_[size_t(d.amplitude)](t_ + step.h) * d.displacement;
}

void PrescribedMotion::take_reaction(const time::StepContext& step, const Eigen::VectorXd& z,
                                     const Eigen::VectorXd& reaction) {
  for (size_t i = 0; i < dofs_.size(); ++i) {
    const int dof = dofs_[i].dof;
    const double force = step.inertia ? reaction[dof] : 0.5 * (reaction_n_[i] + reaction[dof]);  // (5b.7b)
    work_ += force * (z[dof] - step.x_n[dof]);                                                   // (5b.11)
    reaction_n_[i] = reaction[dof];
  }
}

void PrescribedMotion::end_step(const time::StepContext& step, const Eigen::VectorXd&) {
  t_ += step.h;
}

time::TermState PrescribedMotion::save_state() const {
  time::TermState state;
  state.reals["time"] = {t_};
  state.reals["work"] = {work_};
  state.reals["reaction"] = reaction_n_;
  return state;
}

void PrescribedMotion::restore_state(const time::TermState& state, const Eigen::VectorXd&,
                                     const Eigen::VectorXd&) {
  t_ = state.real("time", 1)[0];
  work_ = state.real("work", 1)[0];
  // A checkpoint written before the trapezoid rule has no "reaction": only static steps use it.
  if (state.reals.count("reaction")) reaction_n_ = state.real("reaction", dofs_.size());
}

}  // namespace stoss::run
