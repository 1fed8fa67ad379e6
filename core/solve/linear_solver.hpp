#pragma once
/// @file Sparse direct solver facade over SuiteSparse (UMFPACK through Eigen's support module).

#include <Eigen/Core>
#include <memory>

#include "core/solve/block_pattern.hpp"

namespace stoss::solve {

/// LU solver for general (non-symmetric, indefinite) sparse systems. The symbolic analysis is
/// redone only when the pattern's generation changes; every call refactorises numerically.
class LinearSolver {
 public:
  LinearSolver();
  ~LinearSolver();
  LinearSolver(LinearSolver&&) noexcept;
  LinearSolver& operator=(LinearSolver&&) noexcept;

  /// Factorises A; returns false if the matrix is numerically singular.
  bool factorize(const BlockPattern& A);
  /// Whether a factorisation exists for a matrix of this pattern generation.
  bool ready_for(const BlockPattern& A) const { return factorized_generation_ == A.generation(); }
  /// Number of numeric factorisations so far.
  int factorizations() const { return factorizations_; }
  /// Solves A x = b with the last factorisation.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  /// Seconds spent in analysis, factorisation and solves since construction.
  double seconds() const { return seconds_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int analyzed_generation_ = -1;
  int factorized_generation_ = -1;
  int factorizations_ = 0;
  mutable double seconds_ = 0;
};

}  // namespace stoss::solve
