#pragma once
/// @file A contact pair as the integrator sees it, measuring on the way the force its master exerts on its
/// slave in each converged (sub)step (series/contact_force, docs/results.md): the step's force is at hand
/// only there, before the pair commits the step.

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "core/contact/contact_term.hpp"
#include "core/run/problem.hpp"

namespace stoss::run {

/// Forwards every call to the pair; in end_step, before the pair commits, it takes the discrete force of
/// the master on the slave: f = −Σ_{slave nodes} R_I / c, R the pair's rows at the converged z and c the
/// scheme's force factor (docs/theory.md (5b.12)), friction included.
class MeasuredContact final : public time::Term {
 public:
  explicit MeasuredContact(contact::ContactTerm& pair) : pair_(pair) {}
  /// The force of the last converged (sub)step; 0 before the first.
  const Eigen::Vector3d& slave_force() const { return force_; }

  std::string name() const override { return pair_.name(); }
  double energy(const Eigen::VectorXd& x) const override { return pair_.energy(x); }
  void register_blocks(solve::BlockPattern& pattern) override { pair_.register_blocks(pattern); }
  void prepare_step(const time::StepContext& step) override { pair_.prepare_step(step); }
  void begin_step(const time::StepContext& step, Eigen::VectorXd& z) override { pair_.begin_step(step, z); }
  void add(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
           solve::BlockPattern* K) const override {
    pair_.add(step, z, R, K);
  }
  int auxiliary_count() const override { return pair_.auxiliary_count(); }
  void set_auxiliary_offset(int offset) override { pair_.set_auxiliary_offset(offset); }
  int structure_generation() const override { return pair_.structure_generation(); }
  void initialize_auxiliaries(const time::StepContext& step, Eigen::VectorXd& z) override {
    pair_.initialize_auxiliaries(step, z);
  }
  bool update_active_set(const time::StepContext& step, const Eigen::VectorXd& z) override {
    return pair_.update_active_set(step, z);
  }
  double requested_cut() const override { return pair_.requested_cut(); }
  double auxiliary_residual_measure(const Eigen::VectorXd& R, const time::MeasureScales& s) const override {
    return pair_.auxiliary_residual_measure(R, s);
  }
  double auxiliary_increment_measure(const Eigen::VectorXd& dz, const time::MeasureScales& s) const override {
    return pair_.auxiliary_increment_measure(dz, s);
  }
  void add_impact_impulse(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& b,
                          double& energy_jump) const override {
    pair_.add_impact_impulse(step, z, b, energy_jump);
  }
  void take_reaction(const time::StepContext& step, const Eigen::VectorXd& z,
                     const Eigen::VectorXd& reaction) override {
    pair_.take_reaction(step, z, reaction);
  }
  /// Measures slave_force() at the converged z, then lets the pair commit the step.
  void end_step(const time::StepContext& step, const Eigen::VectorXd& z) override;
  double event_offset() const override { return pair_.event_offset(); }
  time::TermState save_state() const override { return pair_.save_state(); }
  void restore_state(const time::TermState& state, const Eigen::VectorXd& x,
                     const Eigen::VectorXd& v) override {
    pair_.restore_state(state, x, v);
  }

 private:
  contact::ContactTerm& pair_;
  Eigen::Vector3d force_ = Eigen::Vector3d::Zero();
};

/// Each contact pair of `p` behind a MeasuredContact, which measures its force on the slave.
std::vector<std::unique_ptr<MeasuredContact>> measured_pairs(const Problem& p);

/// The integrator's terms: the problem's, its contact pairs (the last ones) behind their measurements.
std::vector<time::Term*> terms_of(const Problem& p,
                                  const std::vector<std::unique_ptr<MeasuredContact>>& pairs);

}  // namespace stoss::run
