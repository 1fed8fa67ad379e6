#pragma once
/// @file Newton's method on a sparse nonlinear system, with backtracking when a full step fails.

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "core/solve/block_pattern.hpp"
#include "core/solve/linear_solver.hpp"

namespace stoss::solve {

/// A square nonlinear system R(z) = 0 with its Jacobian.
class NonlinearSystem {
 public:
  virtual ~NonlinearSystem() = default;
  /// R(z) and, when A is given, ∂R/∂z into A (pattern built, values zeroed by the callee).
  virtual void evaluate(const Eigen::VectorXd& z, Eigen::VectorXd& R, BlockPattern* A) = 0;
  /// Dimensionless size of a residual: converged when ≤ tolerance.
  virtual double residual_measure(const Eigen::VectorXd& R) const = 0;
  /// Dimensionless size of an increment: converged when ≤ tolerance.
  virtual double increment_measure(const Eigen::VectorXd& dz) const = 0;
};

struct NewtonOptions {
  double tolerance = 1e-10;
  int max_iterations = 25;
  int max_backtracks = 6;  ///< halvings of a step whose residual is not finite or grew too much
  /// A fresh step is halved (at most max_backtracks times) while its residual exceeds this factor times
  /// the current one: 2 tolerates the transient growth of smooth problems (10 let Newton cycle at a
  /// residual of ~3e-2 on the two balls' step 30 until the step was reduced: docs/measurements.md,
  /// "Newton on hard impacts"); 1 makes it a backtracking line search on the residual for non-smooth
  /// ones (penalty contact and the return map, §5.2).
  double max_residual_growth = 2;
  /// Keep the last factorisation (across iterations and steps) while it contracts the residual by at
  /// least `reuse_contraction` per iteration; refactorise with a fresh Jacobian otherwise. 0.2 (with
  /// broyden_update): 11.4 iterations per step on the two balls, none reduced (0.5: 14.0 and one step
  /// reduced), at the same CPU time on the seed's example (docs/measurements.md, "Newton on hard impacts").
  bool reuse_factorization = true;
  double reuse_contraction = 0.2;
  /// With a reused factorisation, Broyden's update of its inverse from the steps taken since it was
  /// computed (Kelley's limited-memory form): the chord iteration's linear tail becomes superlinear at
  /// the price of a few dot products per iteration.
  bool broyden_update = true;
  /// How the linear systems are solved (LinearSolver::set_method): direct LU or a Krylov method.
  LinearMethod linear = LinearMethod::direct;
};

struct NewtonResult {
  bool converged = false;
  int iterations = 0;             ///< linear solves (with a fresh or a reused factorisation)
  int backtracks = 0;             ///< step halvings taken
  std::vector<double> residuals;  ///< residual_measure after each evaluation
  std::string failure;            ///< why it stopped, when not converged
};

/// Runs Newton from z (updated in place). `log` receives a line whenever backtracking acts.
NewtonResult newton_solve(NonlinearSystem& system, Eigen::VectorXd& z, BlockPattern& A, LinearSolver& solver,
                          const NewtonOptions& options,
                          const std::function<void(const std::string&)>& log = {});

/// "1.20e+00 3.40e-05 ..." for error messages.
std::string format_history(const std::vector<double>& residuals);

}  // namespace stoss::solve
