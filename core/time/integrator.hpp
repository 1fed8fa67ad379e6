#pragma once
/// @file One time step: the scheme's inertia plus every term, solved by Newton (formulation.md (2.3)).

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/solve/newton.hpp"
#include "core/time/scheme.hpp"
#include "core/time/term.hpp"

namespace stoss::time {

/// Turns the terms into one nonlinear system per step and solves it. It does not know which terms exist.
class Integrator : private solve::NonlinearSystem {
 public:
  /// `fixed` marks Dirichlet dofs (3 per node); `length_scale` and `total_mass` set the convergence scales.
  Integrator(const solve::SparseMatrix& mass, std::vector<Term*> terms, std::vector<char> fixed,
             std::unique_ptr<Scheme> scheme, solve::NewtonOptions options, double length_scale, double total_mass);

  /// Completes the initial state (HHT: M a_0 = f_ext − f_int(x_0)).
  void initialize(State& s);
  /// Solves the step t → t + h. On convergence advances s and calls every term's end_step; otherwise
  /// leaves s as it was. `log` receives solver events.
  solve::NewtonResult step(State& s, double h, const std::function<void(const std::string&)>& log = {});

  /// Σ of the terms' potential energies at x.
  double potential_energy(const Eigen::VectorXd& x) const;
  const Scheme& scheme() const { return *scheme_; }
  double linear_solver_seconds() const { return solver_.seconds(); }

 private:
  void evaluate(const Eigen::VectorXd& z, Eigen::VectorXd& R, solve::BlockPattern* A) override;
  double residual_measure(const Eigen::VectorXd& R) const override;
  double increment_measure(const Eigen::VectorXd& dz) const override;
  /// Lays out the auxiliary unknowns and rebuilds the pattern when their number changed.
  int prepare_unknowns();
  void rebuild_pattern(int n);

  const solve::SparseMatrix& mass_;
  std::vector<Term*> terms_;
  std::vector<char> fixed_;  ///< per unknown (positions first, auxiliaries free)
  std::unique_ptr<Scheme> scheme_;
  solve::NewtonOptions options_;
  double length_scale_, total_mass_;

  solve::BlockPattern pattern_;
  solve::LinearSolver solver_;
  int mass_block_ = -1;
  int auxiliary_layout_ = -1;  ///< total auxiliary count the pattern was built for

  // The step being solved (valid inside step()).
  const State* state_ = nullptr;
  std::unique_ptr<StepContext> context_;
  double residual_scale_ = 0;
  bool scale_pending_ = false;
};

}  // namespace stoss::time
