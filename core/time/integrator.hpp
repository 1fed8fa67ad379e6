#pragma once
/// @file One time step: the scheme's inertia plus every term, solved by Newton inside the active-set
/// loop of the contact terms (docs/theory.md (2.3), §3.5).

#include <Eigen/SparseCholesky>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/solve/newton.hpp"
#include "core/time/scheme.hpp"
#include "core/time/term.hpp"

namespace stoss::time {

/// Turns the terms into one nonlinear system per step and solves it. It does not know which terms exist.
/// The step being solved (its state, h, the force rule) lives in a StepEquations object made by step()
/// and passed down as an argument: nothing of a step stays in the integrator between calls.
class Integrator {
 public:
  /// Most Newton solves of one step while terms keep changing their auxiliary sets (§3.5).
  static constexpr int max_active_set_passes = 20;

  /// `fixed` marks Dirichlet dofs (3 per node); `length_scale` and `total_mass` set the convergence scales.
  Integrator(const solve::SparseMatrix& mass, std::vector<Term*> terms, std::vector<char> fixed,
             std::unique_ptr<Scheme> scheme, solve::NewtonOptions options, double length_scale,
             double total_mass);

  /// After each step (and in initialize) v ← P v: the velocity of the massless nodes of docs/theory.md
  /// §4.6.1 follows their donors. An empty P (the default) leaves v alone.
  void set_velocity_map(solve::SparseMatrix P) { velocity_map_ = std::move(P); }
  /// The Jacobian rows whose inertia the pattern holds: on several MPI ranks a rank's own, the only rows it
  /// hands the linear solver (core/parallel/element_share.hpp); every row when empty (the default).
  void keep_inertia_rows(std::vector<char> rows) { inertia_rows_ = std::move(rows); }
  /// Completes the initial state (HHT: M a_0 = f_ext − f_int(x_0)).
  void initialize(State& s);
  /// Most times one step is solved again, shortened to a term's located contact event (§4.6.2).
  static constexpr int max_event_cuts = 6;

  /// Solves the step t → t + h: Newton, repeated while a term changes its active set (at most
  /// max_active_set_passes solves), then the velocity correction (4.12) if a term asks for it. A term
  /// that locates a contact event inside the step (Term::requested_cut) has the step solved again,
  /// ending there (§4.6.2): the step then advances s by advanced() < h only. On convergence advances s
  /// and calls every term's end_step; otherwise leaves s as it was (a term forgets the abandoned step
  /// at its next prepare_step). The result sums iterations and backtracks over the solves and lists
  /// every residual. `log` receives solver events.
  solve::NewtonResult step(State& s, double h, const LogFunction& log = {});
  /// The size of the last converged step: h, or less when it ended at a located contact event.
  double advanced() const { return advanced_; }

  /// The next step starts with a fresh Jacobian pattern and factorisation, as a new integrator would: after a
  /// checkpoint, the run that goes on and a run resumed from it solve the next step alike.
  void forget_factorization() { auxiliary_layout_ = -1; }
  /// The next step starts with a fresh factorisation on the pattern it has. After a checkpoint, where the
  /// terms' structure stays as it is, that is what forget_factorization gives without rebuilding the
  /// pattern: a rebuild for the same terms has the same sparsity and slots, and the linear solver keeps the
  /// analysis of a sparsity, so the numbers are the same bits.
  void refresh_factorization() { solver_.forget_factorization(); }

  /// Σ of the terms' potential energies at x.
  double potential_energy(const Eigen::VectorXd& x) const;
  const Scheme& scheme() const { return *scheme_; }
  /// Seconds in the linear solver's analysis and factorisations, and in its solves, the initial HHT
  /// solve included.
  double linear_factorization_seconds() const {
    return solver_.factorization_seconds() + initial_factorization_seconds_;
  }
  double linear_solve_seconds() const { return solver_.solve_seconds() + initial_solve_seconds_; }
  /// Seconds spent inside term k's calls (terms in constructor order): residual and Jacobian
  /// contributions, block registration, and the per-step hooks (prepare, begin, active set, end).
  double term_seconds(size_t k) const { return term_seconds_.at(k); }
  /// Seconds in the scheme's inertia rows, the mass block of the Jacobian, the pattern's zeroing,
  /// rebuilds and elimination of fixed rows: the assembly that belongs to no term.
  double inertia_seconds() const { return inertia_seconds_; }
  /// The step solver's linear solver, for its counters (Krylov iterations).
  const solve::LinearSolver& linear_solver() const { return solver_; }
  /// Newton solves in the last step (1 + active-set changes).
  int active_set_passes() const { return passes_; }
  /// The force the supports exerted on the held dofs in the last converged step (3 per node, 0 on free
  /// dofs): the step's residual at the held rows over the scheme's force factor, R_i / h (docs/theory.md
  /// (5b.8)), the discrete force whose work enters external_work. Empty before the first step and
  /// without held dofs.
  const Eigen::VectorXd& reaction() const { return reaction_; }
  /// Kinetic energy added by the velocity correction (4.12) in the last step (0 if none).
  double velocity_correction_energy() const { return correction_energy_; }

 private:
  class StepEquations;  ///< (2.3) of one step as a solve::NonlinearSystem (integrator.cpp)
  /// Lays out the auxiliary unknowns and rebuilds the pattern when their number or a term's
  /// structure changed. Returns the number of unknowns.
  int prepare_unknowns();
  /// Sets each term's auxiliary offset, after the positions and the terms before it; returns the unknowns'
  /// count.
  int lay_out_auxiliaries();
  void rebuild_pattern(int n);
  /// z for the current layout: positions from `positions`, auxiliaries from the terms.
  Eigen::VectorXd relayout(const StepContext& step, const Eigen::VectorXd& positions);
  /// Newton passes with active-set updates; false result if a solve fails or the set never settles.
  solve::NewtonResult solve_with_active_set(StepEquations& equations, Eigen::VectorXd& z,
                                            const LogFunction& log);
  /// One solve of the step of `equations` from s (prepare, predict, Newton with active-set updates) into z.
  solve::NewtonResult attempt(const State& s, StepEquations& equations, Eigen::VectorXd& z,
                              const LogFunction& log);
  /// The smallest step fraction the terms ask to cut the step to (Term::requested_cut), or 1.
  double requested_cut() const;
  /// After a converged step: the impact impulse and end_step of every term, the scheme's advance of s by h.
  void finish(State& s, StepEquations& equations, const Eigen::VectorXd& z);
  /// reaction_ at the converged z from the residual the last evaluation left at the held rows.
  void take_reaction(StepEquations& equations, const Eigen::VectorXd& z);
  /// (4.12): v_{n+1} += γ M⁻¹b for the terms' impact impulse b, restoring their energy jump.
  void correct_velocity(State& s, Eigen::VectorXd impulse, double energy_jump);
  /// v ← P v and a ← P a (set_velocity_map), when P is set.
  void map_velocity(State& s) const;

  const solve::SparseMatrix& mass_;
  std::vector<Term*> terms_;
  std::vector<char> fixed_;  ///< per unknown (positions first, auxiliaries free)
  std::unique_ptr<Scheme> scheme_;
  solve::NewtonOptions options_;
  double length_scale_, total_mass_;

  solve::BlockPattern pattern_;
  solve::LinearSolver solver_;
  int mass_block_ = -1;
  std::vector<char> inertia_rows_;          ///< keep_inertia_rows
  int auxiliary_layout_ = -1;               ///< total unknown count the pattern was built for
  std::vector<int> structure_generations_;  ///< per term, at the last rebuild
  std::unique_ptr<Eigen::SimplicialLDLT<solve::SparseMatrix>>
      mass_solver_;  ///< for (4.12), built on first use

  int passes_ = 0;
  double advanced_ = 0;
  solve::SparseMatrix velocity_map_;  ///< set_velocity_map
  double correction_energy_ = 0;
  bool any_fixed_ = false;        ///< some position dof is held: the reaction is measured
  Eigen::VectorXd held_rows_;     ///< the last evaluation's residual at the position rows, before elimination
  Eigen::VectorXd held_rows_at_;  ///< the positions of that evaluation
  Eigen::VectorXd reaction_;      ///< reaction()

  // Timing hooks (wall clock, for the summary's split of the run time).
  std::vector<double> term_seconds_;
  double inertia_seconds_ = 0;
  double initial_factorization_seconds_ = 0, initial_solve_seconds_ = 0;
};

}  // namespace stoss::time
