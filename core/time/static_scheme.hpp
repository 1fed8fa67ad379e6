#pragma once
/// @file Static load steps (`time.scheme: "static"`, docs/theory.md §5b.6): equilibrium at each load level,
/// no inertia; time is only the parameter the amplitudes follow.

#include "core/time/scheme.hpp"

namespace stoss::time {

/// h f(x_{n+1}) = 0 with every term at the step's end (f = f_int − f_ext, (5b.7)): no mass rows, no
/// velocities. The residual keeps the factor h of the dynamic schemes so that the integrator's measures
/// (momentum units, §2.1) apply unchanged.
class Static : public Scheme {
 public:
  ForceRule force_rule() const override { return ForceRule::end_point(1, 0); }
  void add_inertia(const State&, double, const solve::SparseMatrix&, const Eigen::VectorXd&,
                   Eigen::VectorXd&) const override {}
  double inertia_jacobian_factor(double) const override { return 0; }
  /// x_n: the predictor's residual is then h times the step's load increment, the scale the integrator
  /// measures the step's residual by (§2.1); an extrapolation would leave it near 0 on a smooth ramp.
  Eigen::VectorXd predict(const State& s, double) const override { return s.x; }
  /// s.x = x_1 with v = a = 0: a static solution has no kinetic energy.
  void advance(State& s, double h, const Eigen::VectorXd& x_1) const override;
  bool has_inertia() const override { return false; }
};

}  // namespace stoss::time
