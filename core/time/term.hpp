#pragma once
/// @file One physical effect in the discrete equations of a step (architecture.md, "Term").

#include <Eigen/Core>
#include <string>

#include "core/solve/block_pattern.hpp"

namespace stoss::time {

/// How a term evaluates its force inside a step; the scheme chooses (formulation.md §2).
enum class ForceRule {
  midpoint,           ///< f(x_m), tangent ½ K(x_m)                          (2.5)
  discrete_gradient,  ///< energy–momentum: directional derivative of V       (2.6)
  hht,                ///< (1+α) f(x_{n+1}) − α f(x_n)                        (2.11)
};

/// The step being solved.
struct StepContext {
  const Eigen::VectorXd& x_n;  ///< positions at t_n (3 per node)
  const Eigen::VectorXd& v_n;  ///< velocities at t_n
  double h = 0;                ///< step size
  ForceRule rule = ForceRule::discrete_gradient;
  double alpha = 0;            ///< HHT-α parameter (rule == hht)
};

/// A term adds h · f_alg (the scheme's algorithmic force, momentum units) to the position rows of the
/// step residual, its own equations to the rows of its auxiliary unknowns (contact multipliers), and
/// their derivatives with respect to the unknowns z = [x_{n+1}; auxiliaries] to the Jacobian.
class Term {
 public:
  virtual ~Term() = default;
  virtual std::string name() const = 0;
  /// Potential energy stored by the term at positions x (0 for non-conservative terms).
  virtual double energy(const Eigen::VectorXd& x) const { return 0; }
  /// Registers the Jacobian blocks the term writes (called whenever the pattern is rebuilt).
  virtual void register_blocks(solve::BlockPattern& pattern) = 0;
  /// Called once per step before Newton, with the predictor in z (cache what depends on x_n only).
  virtual void begin_step(const StepContext& step, Eigen::VectorXd& z) {}
  /// Adds the term's residual (and, if K is given, its Jacobian) at z.
  virtual void add(const StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                   solve::BlockPattern* K) const = 0;
  /// Number of auxiliary unknowns the term owns in this step (0 for most terms).
  virtual int auxiliary_count() const { return 0; }
  /// Where the term's auxiliary unknowns start in z.
  virtual void set_auxiliary_offset(int offset) {}
  /// After a converged step: commit history (friction slip, active sets).
  virtual void end_step(const StepContext& step, const Eigen::VectorXd& z) {}
};

}  // namespace stoss::time
