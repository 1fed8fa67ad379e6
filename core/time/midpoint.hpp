#pragma once
/// @file Implicit midpoint rule (docs/theory.md §2.2) and the kinematics it shares with the EM scheme.

#include "core/time/scheme.hpp"

namespace stoss::time {

/// x_{n+1} − x_n = h v_m (2.1); inertia residual (2/h) M Δx − 2 M v_n (2.3).
class MidpointKinematics : public Scheme {
 public:
  void add_inertia(const State& s, double h, const solve::SparseMatrix& M, const Eigen::VectorXd& x_1,
                   Eigen::VectorXd& R) const override;
  double inertia_jacobian_factor(double h) const override { return 2.0 / h; }
  void advance(State& s, double h, const Eigen::VectorXd& x_1) const override;
};

/// Forces at the midpoint configuration (2.5): conserves momenta, not energy.
class Midpoint : public MidpointKinematics {
 public:
  ForceRule force_rule() const override { return ForceRule::midpoint(); }
};

}  // namespace stoss::time
