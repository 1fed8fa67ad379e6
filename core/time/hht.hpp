#pragma once
/// @file HHT-α (docs/theory.md §2.4): the dissipative engineering baseline, conserving neither energy
/// nor angular momentum in nonlinear problems.

#include "core/time/scheme.hpp"

namespace stoss::time {

class Hht : public Scheme {
 public:
  explicit Hht(double alpha);
  ForceRule force_rule() const override { return ForceRule::hht; }
  double alpha() const override { return alpha_; }
  void add_inertia(const State& s, double h, const solve::SparseMatrix& M, const Eigen::VectorXd& x_1,
                   Eigen::VectorXd& R) const override;
  double inertia_jacobian_factor(double h) const override { return 1.0 / (beta_ * h); }
  void advance(State& s, double h, const Eigen::VectorXd& x_1) const override;
  bool needs_initial_acceleration() const override { return true; }

 private:
  /// a_{n+1} from the Newmark update (2.10) solved for the acceleration.
  Eigen::VectorXd acceleration(const State& s, double h, const Eigen::VectorXd& x_1) const;
  double alpha_, beta_, gamma_;
};

}  // namespace stoss::time
