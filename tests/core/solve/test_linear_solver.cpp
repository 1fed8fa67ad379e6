// LinearSolver: the iterative path (BiCGSTAB) solves the same systems as the direct one (UMFPACK).
#include <gtest/gtest.h>

#include "core/solve/linear_solver.hpp"

namespace stoss::solve {
namespace {

/// A mass-dominated 3D-like stiffness: tridiagonal coupling within and across 3 components,
/// m/h² on the diagonal, as the step Jacobians of the tumbling sphere are (SPD, diagonally heavy).
BlockPattern step_like_matrix(int nodes, double mass_over_h2) {
  BlockPattern A;
  std::vector<int> blocks;
  for (int e = 0; e + 1 < nodes; ++e) {
    std::vector<int> dofs;
    for (int I : {e, e + 1})
      for (int k = 0; k < 3; ++k) dofs.push_back(3 * I + k);
    blocks.push_back(A.add_block(dofs));
  }
  A.build(3 * nodes);
  A.zero();
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(6, 6);
  k.topLeftCorner(3, 3) = k.bottomRightCorner(3, 3) = Eigen::Matrix3d::Identity() * 1.0;
  k.topRightCorner(3, 3) = k.bottomLeftCorner(3, 3) = -Eigen::Matrix3d::Identity() * 1.0;
  k(0, 4) += 0.2;  // some non-symmetry, as the energy–momentum tangent has
  for (int b : blocks) A.scatter(b, k);
  for (int i = 0; i < 3 * nodes; ++i) A.add_diagonal(i, mass_over_h2);
  return A;
}

Eigen::VectorXd rhs(int n) {
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::sin(0.37 * i) + 0.1 * (i % 7);
  return b;
}

TEST(LinearSolver, IterativeSolvesTheSameSystemAsDirect) {
  const BlockPattern A = step_like_matrix(400, 0.5);
  const Eigen::VectorXd b = rhs(1200);
  LinearSolver direct, iterative(LinearMethod::iterative);
  ASSERT_TRUE(direct.factorize(A));
  ASSERT_TRUE(iterative.factorize(A));
  const Eigen::VectorXd x_direct = direct.solve(b), x_iterative = iterative.solve(b);
  EXPECT_LT((A.matrix() * x_iterative - b).norm(), 1e-9 * b.norm());
  EXPECT_LT((x_iterative - x_direct).norm(), 1e-8 * x_direct.norm());
  EXPECT_EQ(iterative.krylov_solves(), 1);
  EXPECT_GT(iterative.krylov_iterations(), 1) << "a Krylov method, not a direct solve in disguise";
  EXPECT_EQ(iterative.krylov_fallbacks(), 0);
  EXPECT_EQ(direct.krylov_solves(), 0);
}

TEST(LinearSolver, IterativeKeepsItsMatrixWhenThePatternIsRefilled) {
  BlockPattern A = step_like_matrix(50, 2.0);
  const Eigen::VectorXd b = rhs(150);
  LinearSolver iterative(LinearMethod::iterative);
  ASSERT_TRUE(iterative.factorize(A));
  const SparseMatrix kept = A.matrix();
  A.zero();  // Newton refills the pattern while it reuses a factorisation
  for (int i = 0; i < 150; ++i) A.add_diagonal(i, 1.0);
  const Eigen::VectorXd x = iterative.solve(b);
  EXPECT_LT((kept * x - b).norm(), 1e-9 * b.norm()) << "solves with the factorised matrix, as an LU would";
}

TEST(LinearSolver, AnIterativeSolveThatCannotConvergeFallsBackToLu) {
  // A saddle point (a constraint row with a zero diagonal) that Jacobi-preconditioned BiCGSTAB may
  // not solve within its budget: whatever the Krylov method does, the result solves the system.
  BlockPattern A;
  const int block = A.add_block({0, 1, 2}, {0, 1, 2});
  A.build(3);
  A.zero();
  Eigen::Matrix3d m;
  m << 1e-8, 0, 1, 0, 1, 1, 1, 1, 0;
  A.scatter(block, m);
  const Eigen::VectorXd b = Eigen::Vector3d(1, 2, 3);
  LinearSolver iterative(LinearMethod::iterative);
  ASSERT_TRUE(iterative.factorize(A));
  const Eigen::VectorXd x = iterative.solve(b);
  EXPECT_LT((A.matrix() * x - b).norm(), 1e-8);
}

TEST(LinearSolver, SwitchingTheMethodAsksForANewFactorisation) {
  const BlockPattern A = step_like_matrix(10, 1.0);
  LinearSolver solver;
  ASSERT_TRUE(solver.factorize(A));
  EXPECT_TRUE(solver.ready_for(A));
  solver.set_method(LinearMethod::iterative);
  EXPECT_FALSE(solver.ready_for(A));
  ASSERT_TRUE(solver.factorize(A));
  const Eigen::VectorXd b = rhs(30);
  EXPECT_LT((A.matrix() * solver.solve(b) - b).norm(), 1e-9 * b.norm());
}

TEST(LinearSolver, APatternRebuiltToTheSameSparsityKeepsItsAnalysisAndGivesTheSameBits) {
  const Eigen::VectorXd b = rhs(300);
  BlockPattern A = step_like_matrix(100, 1.0);
  LinearSolver kept;
  ASSERT_TRUE(kept.factorize(A));
  const long analyses = LinearSolver::process_analyses();
  A = step_like_matrix(100, 1.0);  // a new generation of the same sparsity (as after a checkpoint)
  ASSERT_TRUE(kept.factorize(A));
  EXPECT_EQ(LinearSolver::process_analyses(), analyses) << "the ordering of an unchanged sparsity is kept";
  LinearSolver fresh;  // as a run resumed from a checkpoint: analysis and factors anew
  ASSERT_TRUE(fresh.factorize(A));
  EXPECT_EQ(LinearSolver::process_analyses(), analyses + 1);
  const Eigen::VectorXd x_kept = kept.solve(b), x_fresh = fresh.solve(b);
  for (Eigen::Index i = 0; i < b.size(); ++i) ASSERT_EQ(x_kept[i], x_fresh[i]) << "entry " << i;
}

}  // namespace
}  // namespace stoss::solve
