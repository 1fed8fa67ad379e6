#include "core/solve/newton.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace stoss::solve {
namespace {

bool acceptable(double trial, double current, double growth) {
  return std::isfinite(trial) && trial <= growth * current + 1e-300;
}

/// Whether the factorisation that produced `trial` from `current` (iteration `it`) is worth keeping:
/// it contracted the residual by at least reuse_contraction, at that rate the tolerance is reached
/// within the iteration budget (one iteration to spare: the increment test lags the residual), and
/// the budget still leaves a fresh Newton its few iterations should the rate slow down.
bool keeps_contracting(double trial, double current, int it, const NewtonOptions& o) {
  if (!(trial <= o.reuse_contraction * current)) return false;
  if (trial <= o.tolerance) return true;
  const int left = o.max_iterations - (it + 1);
  const double needed = std::log(o.tolerance / trial) / std::log(trial / current);
  return left > 4 && needed + 1 <= left;
}

/// A fresh Newton step that no longer halves a residual already near the tolerance, with an increment
/// within it, has hit the round-off floor of the residual (as the CPP of docs/theory.md §3.2 does).
bool stagnated_at_round_off(double trial, double current, double increment, double tolerance) {
  return increment <= tolerance && trial <= 100 * tolerance && trial > 0.5 * current;
}

/// Broyden's ("good") update of a reused factorisation H_0 = J_0⁻¹, in the limited-memory form of
/// Kelley (Iterative Methods for Linear and Nonlinear Equations, §7.3, brsola): the full steps s_0 … s_n
/// taken since the factorisation (s_0 = −H_0 R_0) are enough to apply H_{n+1}. Valid only for full steps:
/// a halved or rejected step clears it.
class BroydenHistory {
 public:
  void clear() { steps_.clear(); }
  /// Turns the chord step z = −H_0 R_{n+1} into Broyden's step −H_{n+1} R_{n+1}.
  Eigen::VectorXd step(Eigen::VectorXd z) const {
    if (steps_.empty()) return z;
    for (size_t j = 0; j + 1 < steps_.size(); ++j)
      z += steps_[j + 1] * (steps_[j].dot(z) / steps_[j].squaredNorm());
    const Eigen::VectorXd& last = steps_.back();
    return z / (1 - last.dot(z) / last.squaredNorm());
  }
  void push(Eigen::VectorXd full_step) { steps_.push_back(std::move(full_step)); }

 private:
  std::vector<Eigen::VectorXd> steps_;
};

/// The error of an iterate reached by a fresh Newton step of size `increment` that contracted the
/// residual from `current` to `trial`: near the solution the error contracts like the residual, so the
/// next increment is about increment × trial / current. Converging on it, rather than on the increment
/// just taken (the error of the previous iterate), saves the last iteration of most solves. Not after a
/// reused or Broyden step: there the residual's contraction overstated the error's (energy drift 5e-11
/// instead of 9e-14 on tumbling_sphere_hard.json with neo-Hookean and tolerance 1e-12).
double error_estimate(bool fresh, double increment, double trial, double current) {
  return fresh && current > 0 ? increment * std::min(1.0, trial / current) : increment;
}

/// One Newton iteration's bookkeeping: the iterate, its residual and its measure.
struct Iterate {
  Eigen::VectorXd z, R;
  double r = 0;
};

/// The iterate z with its residual and the residual's measure.
Iterate evaluated(NonlinearSystem& system, Eigen::VectorXd z) {
  Iterate iterate{std::move(z), Eigen::VectorXd(), 0};
  iterate.R.resize(iterate.z.size());
  system.evaluate(iterate.z, iterate.R, nullptr);
  iterate.r = system.residual_measure(iterate.R);
  return iterate;
}

/// The Jacobian at the iterate, factorised; false, with the failure named, when it is singular.
bool factorize_at(NonlinearSystem& system, Iterate& current, BlockPattern& A, LinearSolver& solver,
                  NewtonResult& result) {
  system.evaluate(current.z, current.R, &A);
  if (solver.factorize(A)) return true;
  result.failure = solver.factorization_failure();
  return false;
}

/// Halves a fresh Newton step −dz while the residual grows by more than max_residual_growth, at most
/// max_backtracks times; `trial` holds the full step on entry and the step taken on return. Returns its
/// scale.
double backtrack(NonlinearSystem& system, const Iterate& current, const Eigen::VectorXd& dz, Iterate& trial,
                 const NewtonOptions& options, NewtonResult& result,
                 const std::function<void(const std::string&)>& log) {
  double scale = 1;
  for (int cut = 0;
       !acceptable(trial.r, current.r, options.max_residual_growth) && cut < options.max_backtracks; ++cut) {
    scale *= 0.5;
    ++result.backtracks;
    if (log)
      log("newton: residual " + format_history({trial.r}) + " after a full step, halving it (scale " +
          std::to_string(scale) + ")");
    trial.z = current.z - scale * dz;
    system.evaluate(trial.z, trial.R, nullptr);
    trial.r = system.residual_measure(trial.R);
  }
  return scale;
}

}  // namespace

std::string format_history(const std::vector<double>& residuals) {
  std::string out;
  char buffer[32];
  for (double r : residuals) {
    std::snprintf(buffer, sizeof buffer, "%s%.2e", out.empty() ? "" : " ", r);
    out += buffer;
  }
  return out;
}

NewtonResult newton_solve(NonlinearSystem& system, Eigen::VectorXd& z, BlockPattern& A, LinearSolver& solver,
                          const NewtonOptions& options, const std::function<void(const std::string&)>& log) {
  NewtonResult result;
  solver.set_method(options.linear);  // a no-op unless the method changed
  Iterate current = evaluated(system, z);
  result.residuals.push_back(current.r);
  if (!std::isfinite(current.r)) {
    result.failure = "residual is not finite at the predictor";
    return result;
  }
  double increment = 0;  // the error estimate of the current iterate, once it has moved
  BroydenHistory broyden;
  bool refactor = !options.reuse_factorization || !solver.ready_for(A);
  for (int it = 0; it <= options.max_iterations; ++it) {
    if (current.r <= options.tolerance && (it == 0 || increment <= options.tolerance)) {
      z = current.z;
      result.converged = true;
      return result;
    }
    if (it == options.max_iterations) break;
    const bool fresh = refactor;
    if (fresh) {
      if (!factorize_at(system, current, A, solver, result)) return result;
      refactor = !options.reuse_factorization;
      broyden.clear();
    }
    Eigen::VectorXd dz = solver.solve(current.R);
    if (!fresh && options.broyden_update) dz = -broyden.step(-dz);
    increment = system.increment_measure(dz);
    ++result.iterations;
    Iterate trial = evaluated(system, current.z - dz);
    if (!fresh && !keeps_contracting(trial.r, current.r, it, options)) {
      refactor = true;  // the old factorisation no longer pays: refactorise at the better iterate
      broyden.clear();
      if (!(trial.r < current.r)) continue;
    }
    const double scale = fresh ? backtrack(system, current, dz, trial, options, result, log) : 1.0;
    increment *= scale;
    if (fresh && stagnated_at_round_off(trial.r, current.r, increment, options.tolerance)) {
      z = trial.z;
      result.residuals.push_back(trial.r);
      result.converged = true;
      if (log) log("newton: residual stagnated at " + format_history({trial.r}) + " (round-off), accepted");
      return result;
    }
    if (fresh && !keeps_contracting(trial.r, current.r, it, options)) refactor = true;
    if (scale == 1 && !refactor)
      broyden.push(-dz);
    else
      broyden.clear();
    increment = error_estimate(fresh, increment, trial.r, current.r);
    current = std::move(trial);
    result.residuals.push_back(current.r);
    if (!std::isfinite(current.r)) {
      result.failure = "residual is not finite";
      return result;
    }
  }
  result.failure = "no convergence in " + std::to_string(options.max_iterations) + " iterations";
  return result;
}

}  // namespace stoss::solve
