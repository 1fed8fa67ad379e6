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
  /// The secant predictor x_n + (h/2)(v_n + v_{n−1}) = x_n + h v_n − (h h_{n−1}/2) a_n: for a stiff
  /// mode (ωh ≫ 1) the midpoint rule flips v every step, so x_n + h v_n is off by ~h v_n where the
  /// secant is right, and on a smooth motion both are off by O(h² a). On the two balls it halved Newton's
  /// iterations (docs/measurements.md, "Newton on hard impacts"). With h_{n−1} = s.last_step it holds
  /// for steps of any size (a step cut at a contact event, docs/theory.md §4.6.2, or a step controller's).
  Eigen::VectorXd predict(const State& s, double h) const override;
  /// Also sets s.a to the step's mean acceleration (v_{n+1} − v_n)/h and s.last_step to h, for the predictor.
  void advance(State& s, double h, const Eigen::VectorXd& x_1) const override;
};

/// Forces at the midpoint configuration (2.5): conserves momenta, not energy.
class Midpoint : public MidpointKinematics {
 public:
  ForceRule force_rule() const override { return ForceRule::midpoint(); }
};

}  // namespace stoss::time
