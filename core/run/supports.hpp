#pragma once
/// @file Supports with prescribed motion (scene `boundary[i].displacement`, docs/theory.md §5b.9): the held
/// dofs follow x = X + a(t)·u, and the work the supports do enters series/external_work.

#include <Eigen/Core>
#include <vector>

#include "core/loads/amplitude.hpp"
#include "core/time/term.hpp"

namespace stoss::run {

/// One prescribed dof: x_i(t) = X_i + a(t) u_i, a the amplitude of the boundary entry that holds it first.
struct PrescribedDof {
  int dof;
  double reference;     ///< X_i
  double displacement;  ///< u_i
  int amplitude;        ///< index into PrescribedMotion's amplitudes
};

/// The supports that move, as a term: it writes x_{n+1} of its dofs into the step's unknowns before
/// Newton (the integrator holds them there, as it holds every fixed dof), and counts the reaction's work
/// Σ r_i (x_{n+1} − x_n)_i in the step's discrete form (5b.11). Adds nothing to the residual.
class PrescribedMotion final : public time::Term {
 public:
  PrescribedMotion(std::vector<PrescribedDof> dofs, std::vector<loads::Amplitude> amplitudes);
  std::string name() const override { return "prescribed_motion"; }
  void register_blocks(solve::BlockPattern&) override {}
  /// x_{n+1} = X + a(t_n + h) u on the prescribed dofs (the integrator leaves them there).
  void begin_step(const time::StepContext& step, Eigen::VectorXd& z) override;
  void add(const time::StepContext&, const Eigen::VectorXd&, Eigen::VectorXd&,
           solve::BlockPattern*) const override {}
  /// Adds Σ r_i Δx_i over the prescribed dofs to the work (5b.11); in static steps Σ ½ (r_n,i + r_i) Δx_i,
  /// the trapezoid rule between two equilibria (5b.7b).
  void take_reaction(const time::StepContext& step, const Eigen::VectorXd& z,
                     const Eigen::VectorXd& reaction) override;
  /// Advances the clock by h.
  void end_step(const time::StepContext& step, const Eigen::VectorXd& z) override;
  /// "time", "work" and "reaction": the clock, the supports' work so far and the last step's reaction on
  /// the prescribed dofs (the trapezoid rule's r_n).
  time::TermState save_state() const override;
  void restore_state(const time::TermState& state, const Eigen::VectorXd& x,
                     const Eigen::VectorXd& v) override;
  /// Σ over the converged steps of the supports' work (5b.11): their part of series/external_work.
  double work() const { return work_; }

 private:
  std::vector<PrescribedDof> dofs_;
  std::vector<loads::Amplitude> amplitudes_;
  double t_ = 0;
  double work_ = 0;
  std::vector<double> reaction_n_;  ///< the last converged step's reaction per prescribed dof
};

}  // namespace stoss::run
