#include "core/run/solver_choice.hpp"

#include <algorithm>
#include <cstdio>

#include "core/parallel/element_share.hpp"

namespace stoss::run {

solve::LinearMethod linear_method(const model::Model& m) {
  switch (m.solver.linear) {
    case model::LinearSolver::iterative:
      return solve::LinearMethod::iterative;
    case model::LinearSolver::petsc_gamg:
      return solve::LinearMethod::petsc_gamg;
    case model::LinearSolver::direct:  // UMFPACK is sequential: on several ranks, MUMPS through PETSc
      return parallel::element_share().shared() ? solve::LinearMethod::petsc_mumps
                                                : solve::LinearMethod::direct;
    case model::LinearSolver::automatic:
      break;
  }
  return m.mesh.element_count() >= auto_iterative_elements(m) ? solve::LinearMethod::petsc_gamg
                                                              : solve::LinearMethod::direct;
}

int auto_iterative_elements(const model::Model& m) {
  return m.contact.empty() ? model::SolverSpec::auto_iterative_elements
                           : model::SolverSpec::auto_iterative_elements_with_contact;
}

std::string linear_solver_line(const model::Model& m) {
  const solve::LinearMethod method = linear_method(m);
  const std::string name =
      method == solve::LinearMethod::petsc_gamg    ? "petsc_gamg (PETSc GMRES + GAMG, rigid-body modes)"
      : method == solve::LinearMethod::iterative   ? "iterative (BiCGSTAB, Jacobi preconditioner)"
      : method == solve::LinearMethod::petsc_mumps ? "direct (MUMPS LU through PETSc, over the ranks)"
                                                   : "direct (UMFPACK LU)";
  if (m.solver.linear != model::LinearSolver::automatic) return "linear solver: " + name;
  return "linear solver: auto → " + name + ": " + std::to_string(m.mesh.element_count()) +
         " elements, petsc_gamg from " + std::to_string(auto_iterative_elements(m)) +
         (m.contact.empty() ? "" : " with contact");
}

std::string krylov_line(const solve::LinearSolver& linear) {
  char line[200];
  std::snprintf(
      line, sizeof line,
      "linear solver: %ld Krylov solves, %.1f iterations per solve, at most %d, %ld fell back to LU",
      linear.krylov_solves(), double(linear.krylov_iterations()) / double(linear.krylov_solves()),
      linear.krylov_max_iterations(), linear.krylov_fallbacks());
  return line;
}

/// Factorisations are kept while they contract the residual by 5 per iteration with Broyden's update (and
/// reach the tolerance within the budget): on the contact scenes a refactorisation costs as much as ~20
/// reused solves (bench/contact_ball.cpp); NewtonOptions holds the reuse rule (docs/measurements.md,
/// "Newton on hard impacts").
solve::NewtonOptions newton_options(const model::Model& m) {
  solve::NewtonOptions o;
  o.linear = linear_method(m);
  // A GAMG setup is cheap next to an LU but each GMRES solve costs 13–24 multigrid cycles: a fresh
  // Jacobian per iteration halved Newton's iterations (4 instead of 8.5 per step) and the wall time
  // (21.8 s instead of 45.6 s, 2 steps of the 27,648-hex8 tumbling sphere). The AMG solver itself keeps
  // its setup for the new matrix while GMRES converges about as fast (petsc_amg_solver.cpp).
  if (o.linear == solve::LinearMethod::petsc_gamg) o.reuse_factorization = false;
  o.tolerance = m.solver.tolerance;
  o.max_iterations = m.solver.max_iterations;
  const bool penalty = std::any_of(m.contact.begin(), m.contact.end(), [](const model::ContactPair& c) {
    return c.enforcement == model::Enforcement::penalty;
  });
  if (penalty) o.max_residual_growth = 1;  // line search: penalty and the return map are non-smooth (§5.2)
  return o;
}

void report_linear_solver(const solve::LinearSolver& linear, model::Summary& sum, model::Observer& observer) {
  if (linear.krylov_solves() > 0)
    sum.krylov_iterations_per_solve = double(linear.krylov_iterations()) / double(linear.krylov_solves());
  sum.krylov_fallbacks = int(linear.krylov_fallbacks());
  if (linear.krylov_solves() > 0) observer.log(krylov_line(linear));
  if (!linear.preconditioner_description().empty())
    observer.log("linear solver: " + linear.preconditioner_description());
}

}  // namespace stoss::run
