#pragma once
/// @file Time schemes: how x_{n+1} determines v_{n+1}, the inertia part of the step residual, and the
/// force rule the terms use (docs/theory.md §2). One file per scheme.

#include <Eigen/Core>
#include <memory>

#include "core/model/model.hpp"
#include "core/solve/block_pattern.hpp"
#include "core/time/term.hpp"

namespace stoss::time {

/// Positions, velocities and accelerations at t, stacked 3 per node. The accelerations are the
/// scheme's: HHT's and generalized-α's a_n (2.10); the midpoint schemes' mean acceleration of the last
/// step, (v_n − v_{n−1}) / h, which their predictor uses (midpoint.hpp).
struct State {
  Eigen::VectorXd x, v, a;
  double t = 0;
  /// h of the step that ended here (midpoint-type schemes, for the predictor); 0 before the first step
  /// and in a state restored without it, where the next step's h stands in.
  double last_step = 0;
  int step = 0;
};

class Scheme {
 public:
  virtual ~Scheme() = default;
  /// Where and with which weights the terms evaluate their force (term.hpp).
  virtual ForceRule force_rule() const = 0;
  /// The factor on the algorithmic forces in the momentum rows of the step residual: h for every scheme
  /// of docs/theory.md §2, whose residuals (2.3), h × (2.11), h × (2.12) are momenta.
  virtual double force_factor(double h) const { return h; }
  /// Adds the inertia part of the residual (momentum units) at x_1 to R.
  virtual void add_inertia(const State& s, double h, const solve::SparseMatrix& M, const Eigen::VectorXd& x_1,
                           Eigen::VectorXd& R) const = 0;
  /// c with ∂(inertia residual)/∂x_1 = c M.
  virtual double inertia_jacobian_factor(double h) const = 0;
  /// Newton's starting point for x_{n+1}: x_n + h v_n unless the scheme knows better.
  virtual Eigen::VectorXd predict(const State& s, double h) const { return s.x + h * s.v; }
  /// Sets s.x = x_1 and the matching velocity (and acceleration); does not touch t.
  virtual void advance(State& s, double h, const Eigen::VectorXd& x_1) const = 0;
  /// Whether the scheme needs an initial acceleration (HHT: M a_0 = f_ext − f_int(x_0)).
  virtual bool needs_initial_acceleration() const { return false; }
  /// False for static load steps, which solve equilibria without a mass row (§5b.6).
  virtual bool has_inertia() const { return true; }
};

/// The scheme a model asks for: the registry of schemes (scheme.cpp), one line each.
std::unique_ptr<Scheme> make_scheme(const model::TimeSpec& time);

}  // namespace stoss::time
