#pragma once
/// @file One physical effect in the discrete equations of a step (docs/architecture.md, "Terms").

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/solve/block_pattern.hpp"

namespace stoss::time {

/// How the terms evaluate their force f_alg inside a step t_n → t_{n+1}; the scheme chooses it, the terms
/// apply it (docs/theory.md §2). Two kinds cover every scheme of §2:
///   configuration:      f_alg = w f(x_θ) + w_n f(x_n),  x_θ = (1−θ) x_n + θ x_{n+1},
///                       ∂f_alg/∂x_{n+1} = w θ K(x_θ)   (midpoint (2.5), HHT-α (2.11), generalized-α (2.12));
///   discrete_gradient:  f_alg = the discrete gradient of V between x_n and x_{n+1} (2.6).
struct ForceRule {
  enum class Kind { configuration, discrete_gradient };
  Kind kind = Kind::discrete_gradient;
  double theta = 1;            ///< where the configuration force is evaluated
  double weight = 1;           ///< w, on f(x_θ)
  double previous_weight = 0;  ///< w_n, on f(x_n) (the force at the start of the step)

  static ForceRule discrete_gradient() { return {}; }
  /// f(x_m), x_m = ½ (x_n + x_{n+1}) (2.5).
  static ForceRule midpoint() { return {Kind::configuration, 0.5, 1, 0}; }
  /// w f(x_{n+1}) + w_n f(x_n): HHT-α (2.11) and generalized-α (2.12).
  static ForceRule end_point(double weight, double previous_weight) {
    return {Kind::configuration, 1, weight, previous_weight};
  }
  bool is_midpoint() const { return kind == Kind::configuration && theta == 0.5 && previous_weight == 0; }
  bool is_end_point() const { return kind == Kind::configuration && theta == 1; }
  /// x_θ from x_n and x_{n+1}.
  template <class Vector>
  Vector evaluation_point(const Vector& x_n, const Vector& x_1) const {
    return theta == 1 ? Vector(x_1) : Vector((1 - theta) * x_n + theta * x_1);
  }
};

/// Receives solver events (a line each).
using LogFunction = std::function<void(const std::string&)>;

/// The step being solved.
struct StepContext {
  const Eigen::VectorXd& x_n;  ///< positions at t_n (3 per node)
  const Eigen::VectorXd& v_n;  ///< velocities at t_n
  double h = 0;                ///< step size
  ForceRule rule = ForceRule::discrete_gradient();
  const LogFunction* log = nullptr;  ///< solver log of the run; may be null
  /// The factor the scheme puts on every algorithmic force in the momentum rows of (2.3) (Scheme::
  /// force_factor): terms add force_factor · f_alg, so that they never multiply by h themselves.
  double force_factor = h;
  /// Whether a term may still ask to cut this step at a located contact event (Term::requested_cut);
  /// false once the integrator's cuts are spent: a term then handles the event inside the step.
  bool may_cut = false;
  /// False in static load steps (§5b.6): loads and moving supports then count their work between two
  /// equilibria by the trapezoid rule (5b.7b), not as f_alg·Δx.
  bool inertia = true;
};

/// What a term carries from one converged step to the next (active set, multipliers, friction history), as
/// named flat arrays: what a checkpoint stores for the term (core/run/checkpoint.hpp) and gives back
/// to it on resume.
struct TermState {
  std::map<std::string, std::vector<double>> reals;
  std::map<std::string, std::vector<std::int64_t>> integers;

  /// The array `name` with `size` entries. @throws std::invalid_argument naming the array and the size.
  template <class T>
  static const std::vector<T>& sized(const std::map<std::string, std::vector<T>>& arrays,
                                     const std::string& name, size_t size) {
    const auto it = arrays.find(name);
    if (it == arrays.end()) throw std::invalid_argument("term state: array '" + name + "' is missing");
    if (it->second.size() != size)
      throw std::invalid_argument("term state: array '" + name + "' has " +
                                  std::to_string(it->second.size()) + " entries, expected " +
                                  std::to_string(size));
    return it->second;
  }
  const std::vector<double>& real(const std::string& name, size_t size) const {
    return sized(reals, name, size);
  }
  const std::vector<std::int64_t>& integer(const std::string& name, size_t size) const {
    return sized(integers, name, size);
  }
};

/// Scales that make a term's rows and increments dimensionless (Integrator::residual_measure).
struct MeasureScales {
  double momentum = 1;  ///< scale of the position rows of (2.3): ‖2 M v_n‖, the predictor residual or a floor
  double length = 1;  ///< model length (bounding-box diagonal)
};

/// A term adds step.force_factor · f_alg (momentum units: the scheme's factor, h for every scheme of §2,
/// times the algorithmic force the scheme's ForceRule asks for) to the position rows of the step
/// residual, its own equations to the rows of its auxiliary unknowns (contact multipliers), and
/// their derivatives with respect to the unknowns z = [x_{n+1}; auxiliaries] to the Jacobian.
///
/// Order of calls in a step (Integrator::step): prepare_step → layout (auxiliary_count,
/// set_auxiliary_offset, register_blocks if the pattern changed) → begin_step → Newton (add) →
/// update_active_set; while any term changed its set: layout → initialize_auxiliaries → Newton →
/// update_active_set. Then add_impact_impulse and end_step.
class Term {
 public:
  virtual ~Term() = default;
  virtual std::string name() const = 0;
  /// Potential energy stored by the term at positions x (0 for non-conservative terms).
  virtual double energy(const Eigen::VectorXd& x) const { return 0; }
  /// Registers the Jacobian blocks the term writes (called whenever the pattern is rebuilt).
  virtual void register_blocks(solve::BlockPattern& pattern) = 0;
  /// Called once per step before the unknowns are laid out; a term may change its auxiliary set here
  /// (contact: search, face switches at t_n).
  virtual void prepare_step(const StepContext& step) {}
  /// Called once per step before Newton, with the predictor in z (cache what depends on x_n only; a
  /// term with auxiliaries writes their initial values).
  virtual void begin_step(const StepContext& step, Eigen::VectorXd& z) {}
  /// Adds the term's residual (and, if K is given, its Jacobian) at z.
  virtual void add(const StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                   solve::BlockPattern* K) const = 0;
  /// Number of auxiliary unknowns the term owns in this step (0 for most terms).
  virtual int auxiliary_count() const { return 0; }
  /// Where the term's auxiliary unknowns start in z.
  virtual void set_auxiliary_offset(int offset) {}
  /// Changes whenever the blocks the term registers change, even if auxiliary_count() does not
  /// (contact: an element moved to another face). The integrator rebuilds the pattern on a change.
  virtual int structure_generation() const { return 0; }
  /// After a re-layout inside a step: writes the initial values of the auxiliaries into z, whose
  /// positions hold the current iterate.
  virtual void initialize_auxiliaries(const StepContext& step, Eigen::VectorXd& z) {}
  /// After Newton converged with the current auxiliary set: updates the set from the solution z
  /// (the contact active set, docs/theory.md §3.5). Returns true if it changed.
  virtual bool update_active_set(const StepContext& step, const Eigen::VectorXd& z) { return false; }
  /// After update_active_set: the fraction of the step at whose end the term's earliest located contact
  /// event lies (docs/theory.md §4.6.2), or 1 when the step may run to its end. A fraction < 1 makes the
  /// integrator solve the step again, shortened to it.
  virtual double requested_cut() const { return 1; }
  /// Dimensionless size of the term's auxiliary rows in R (the largest over its groups of rows of
  /// like units). Terms that own auxiliaries override it; converged when ≤ the Newton tolerance.
  virtual double auxiliary_residual_measure(const Eigen::VectorXd& R, const MeasureScales& s) const {
    return 0;
  }
  /// Dimensionless size of the term's auxiliary part of a Newton increment.
  virtual double auxiliary_increment_measure(const Eigen::VectorXd& dz, const MeasureScales& s) const {
    return 0;
  }
  /// After a converged step, before end_step: adds the term's impact impulse b (momentum units, 3 per
  /// node) and its energy jump ΔH to be restored by the velocity correction (4.12); most terms add
  /// nothing.
  virtual void add_impact_impulse(const StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& b,
                                  double& energy_jump) const {}
  /// After a converged step, before end_step, when some dof is held: `reaction` (3 per node) is the force the
  /// supports exert on the held dofs in the step's discrete form (Integrator::reaction); 0 on free dofs.
  virtual void take_reaction(const StepContext& step, const Eigen::VectorXd& z,
                             const Eigen::VectorXd& reaction) {}
  /// After a converged step: commit history (friction slip, active sets).
  virtual void end_step(const StepContext& step, const Eigen::VectorXd& z) {}
  /// After end_step: the largest position offset the term's own model put in during the last converged
  /// step, in length units, which no truncation-error estimate sees: a contact constraint that starts
  /// with a frozen gap (persist, docs/theory.md §4.5) keeps the body that far off the face. A step
  /// controller adds it to its error estimate. 0 for most terms.
  virtual double event_offset() const { return 0; }
  /// Between two steps (after end_step): the history the next step needs (checkpoint). Empty for terms
  /// that keep none (elasticity, gravity: everything they use is recomputed from x_n).
  virtual TermState save_state() const { return {}; }
  /// On resume, in place of the steps before: sets the history save_state gave after the step that ended
  /// at positions `x` and velocities `v`, as if that step had just converged in this run.
  /// @throws std::invalid_argument when `state` does not fit the term (TermState::real, integer).
  virtual void restore_state(const TermState& state, const Eigen::VectorXd& x, const Eigen::VectorXd& v) {}
};

}  // namespace stoss::time
