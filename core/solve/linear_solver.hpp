#pragma once
/// @file Sparse linear solver facade: SuiteSparse UMFPACK (direct, the default), a preconditioned
/// Krylov method (iterative, Eigen's BiCGSTAB), or GMRES with PETSc's algebraic multigrid (petsc_gamg).

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>

#include "core/solve/block_pattern.hpp"

namespace stoss::solve {

/// How LinearSolver solves. `iterative` is BiCGSTAB with a Jacobi preconditioner on a copy of the
/// factorised matrix (no AMG: see docs/measurements.md, "Performance"); a solve that does not reach its
/// tolerance falls back to an LU of the same matrix, so Newton always receives a solution of that matrix.
/// `petsc_gamg` is GMRES preconditioned by PETSc's algebraic multigrid (GAMG) with the rigid-body
/// modes as near-null space (core/solve/petsc_solver.hpp), with the same LU fallback. `petsc_mumps` is
/// MUMPS's LU through PETSc, the direct solver of a run on several MPI ranks (docs/many_machines.md).
enum class LinearMethod { direct, iterative, petsc_gamg, petsc_mumps };

/// Solver for general (non-symmetric, indefinite) sparse systems. Direct: LU, the symbolic analysis
/// redone only when the pattern's generation changes, every factorize() refactorises numerically.
/// Iterative: factorize() keeps the matrix and its preconditioner, solve() runs BiCGSTAB.
class LinearSolver {
 public:
  explicit LinearSolver(LinearMethod method = LinearMethod::direct);
  ~LinearSolver();
  LinearSolver(LinearSolver&&) noexcept;
  LinearSolver& operator=(LinearSolver&&) noexcept;

  /// Switches the method; the next solve needs a new factorize().
  void set_method(LinearMethod method);
  LinearMethod method() const { return method_; }
  /// Factorises A (iterative: keeps a copy of A and builds the preconditioner); returns false if the
  /// matrix is numerically singular.
  bool factorize(const BlockPattern& A);
  /// Why the last factorize() returned false: "singular Jacobian", or the direct solver's own failure
  /// when it is not singularity (UMFPACK out of memory).
  std::string factorization_failure() const;
  /// The next ready_for() is false: Newton factorises anew, the symbolic analysis stays.
  void forget_factorization() { factorized_generation_ = -1; }
  /// Whether a factorisation exists for a matrix of this pattern generation.
  bool ready_for(const BlockPattern& A) const { return factorized_generation_ == A.generation(); }
  /// Positions of the nodes (3 per node) whose dofs come first in every matrix; the AMG path builds
  /// the rigid-body modes from them. The other methods ignore them.
  void set_coordinates(const Eigen::VectorXd& positions) { coordinates_ = positions; }
  /// Number of numeric factorisations so far.
  int factorizations() const { return factorizations_; }
  /// Numeric factorisations and solves of every LinearSolver of this process so far (bench/seed_counts.cpp
  /// reports them for a whole run).
  static long process_factorizations();
  static long process_solves();
  /// Symbolic analyses (orderings) of every LinearSolver of this process so far.
  static long process_analyses();
  /// Solves A x = b with the last factorisation.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  /// Seconds since construction in analysis and factorisations (petsc_gamg: copying the matrix in and
  /// setting up the preconditioner), and in solves (Krylov iterations, and an LU a failed Krylov solve
  /// falls back to).
  double factorization_seconds() const { return factorization_seconds_; }
  double solve_seconds() const { return solve_seconds_; }

  /// Iterative method: relative residual ‖b − A x‖ / ‖b‖ a Krylov solve stops at.
  static constexpr double krylov_tolerance = 1e-10;
  /// Iterative method: Krylov iterations a solve may take before it falls back to LU.
  static constexpr int max_krylov_iterations = 1000;
  /// Iterative methods: solves so far, their Krylov iterations in total and the most one solve took,
  /// and the solves that fell back to LU.
  long krylov_solves() const { return krylov_solves_; }
  long krylov_iterations() const { return krylov_iterations_; }
  int krylov_max_iterations() const { return krylov_max_iterations_; }
  long krylov_fallbacks() const { return krylov_fallbacks_; }
  /// petsc_gamg: relative residual its GMRES solves stop at (default amg_default_tolerance, 1e-4:
  /// Newton corrects the rest, so the answer still meets the Newton tolerance).
  void set_krylov_tolerance(double relative);
  /// petsc_gamg: the Krylov method and preconditioner of the last factorisation (empty otherwise).
  std::string preconditioner_description() const;

 private:
  struct Impl;
  struct Krylov;
  struct Amg;
  bool factorize_amg(const BlockPattern& A);
  bool through_petsc() const {
    return method_ == LinearMethod::petsc_gamg || method_ == LinearMethod::petsc_mumps;
  }
  Eigen::VectorXd solve_amg(const Eigen::VectorXd& b) const;
  /// Counts a Krylov solve of A x = b that took `iterations`; when it did not converge (or x is not
  /// finite), solves A directly instead, factorising A (asked of `matrix` only then) once, `lu_ready`,
  /// for the solves that follow.
  Eigen::VectorXd checked_krylov(Eigen::VectorXd x, int iterations, bool converged,
                                 const std::function<SparseMatrix()>& matrix, bool& lu_ready,
                                 const Eigen::VectorXd& b) const;
  std::unique_ptr<Impl> impl_;
  std::unique_ptr<Krylov> krylov_;
  std::unique_ptr<Amg> amg_;
  Eigen::VectorXd coordinates_;
  double amg_tolerance_ = 0;  ///< 0: the AMG solver's default
  LinearMethod method_ = LinearMethod::direct;
  int analyzed_generation_ = -1;
  int factorized_generation_ = -1;
  int factorizations_ = 0;
  double factorization_seconds_ = 0;
  mutable double solve_seconds_ = 0;
  mutable long krylov_solves_ = 0, krylov_iterations_ = 0, krylov_fallbacks_ = 0;
  mutable int krylov_max_iterations_ = 0;
};

}  // namespace stoss::solve
