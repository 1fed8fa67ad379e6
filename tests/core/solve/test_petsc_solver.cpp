// LinearSolver's petsc_gamg path (GMRES + GAMG with rigid-body modes; Schur field split with contact
// rows) solves the same systems as the direct one (UMFPACK), with bounded Krylov iterations.
#include <gtest/gtest.h>

#include "core/solve/linear_solver.hpp"
#include "core/solve/petsc_solver.hpp"

namespace stoss::solve {
namespace {

/// A small elastic system: a cubic lattice of n³ nodes joined by bars to their 26 neighbours (its
/// stiffness has exactly the six rigid-body modes as null space), plus mass/h² on the diagonal, as
/// a step Jacobian has. Stiffness k (e ⊗ e) per bar of direction e.
struct Lattice {
  int n = 0;
  Eigen::VectorXd positions;
  int node(int i, int j, int k) const { return i + n * (j + n * k); }
};

Lattice lattice(int n) {
  Lattice l{n, Eigen::VectorXd(3 * n * n * n)};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        l.positions.segment<3>(3 * l.node(i, j, k)) = Eigen::Vector3d(i, j, k) / (n - 1.0);
  return l;
}

/// Adds the bars' blocks; with `constrained` nodes, one multiplier row each ties the node's normal
/// displacement n·u = 0 (a zero diagonal: the saddle point of Lagrange contact).
BlockPattern elastic_system(const Lattice& l, double mass_over_h2, const std::vector<int>& constrained = {}) {
  BlockPattern A;
  std::vector<std::pair<int, Eigen::MatrixXd>> blocks;
  const int n = l.n, nodes = n * n * n;
  auto dofs_of = [](std::initializer_list<int> ns) {
    std::vector<int> d;
    for (int a : ns)
      for (int c = 0; c < 3; ++c) d.push_back(3 * a + c);
    return d;
  };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (int dk = 0; dk <= 1; ++dk)
          for (int dj = dk ? -1 : 0; dj <= 1; ++dj)
            for (int di = (dk || dj) ? -1 : 1; di <= 1; ++di) {
              const int I = i + di, J = j + dj, K = k + dk;
              if (I < 0 || J < 0 || I >= n || J >= n || K >= n) continue;
              const int a = l.node(i, j, k), b = l.node(I, J, K);
              const Eigen::Vector3d e =
                  (l.positions.segment<3>(3 * b) - l.positions.segment<3>(3 * a)).normalized();
              Eigen::MatrixXd kb(6, 6);
              const Eigen::Matrix3d ee = e * e.transpose();
              kb << ee, -ee, -ee, ee;
              blocks.emplace_back(A.add_block(dofs_of({a, b})), kb);
            }
  const int m = 3 * nodes;
  std::vector<int> rows;
  for (size_t c = 0; c < constrained.size(); ++c) {
    std::vector<int> block = dofs_of({constrained[c]});
    block.push_back(m + int(c));
    Eigen::MatrixXd g = Eigen::MatrixXd::Zero(4, 4);
    g(2, 3) = g(3, 2) = 1;  // n = e_z
    blocks.emplace_back(A.add_block(block), g);
  }
  A.build(m + int(constrained.size()));
  A.zero();
  for (const auto& [id, values] : blocks) A.scatter(id, values);
  for (int i = 0; i < m; ++i) A.add_diagonal(i, mass_over_h2);
  return A;
}

Eigen::VectorXd rhs(int n) {
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::sin(0.37 * i) + 0.1 * (i % 7);
  return b;
}

/// A petsc_gamg solver with the rigid-body modes of `positions`, GMRES to a relative residual of 1e-10.
LinearSolver tight_amg(const Eigen::VectorXd& positions) {
  LinearSolver amg(LinearMethod::petsc_gamg);
  amg.set_coordinates(positions);
  amg.set_krylov_tolerance(1e-10);
  return amg;
}

/// Solves with both methods, GMRES to a relative residual of 1e-10, and checks that they agree;
/// returns the petsc solver for its counters.
LinearSolver expect_same_solution(const BlockPattern& A, const Eigen::VectorXd& positions) {
  const Eigen::VectorXd b = rhs(A.matrix().rows());
  LinearSolver direct, amg = tight_amg(positions);
  EXPECT_TRUE(direct.factorize(A));
  EXPECT_TRUE(amg.factorize(A));
  const Eigen::VectorXd x_direct = direct.solve(b), x_amg = amg.solve(b);
  EXPECT_LT((A.matrix() * x_amg - b).norm(), 1e-9 * b.norm());
  EXPECT_LT((x_amg - x_direct).norm(), 1e-8 * x_direct.norm());
  EXPECT_EQ(amg.krylov_fallbacks(), 0) << "solved by GMRES, not by the LU fallback";
  return amg;
}

TEST(PetscGamg, TheSystemShallSolveASmallElasticSystemAsTheDirectSolverDoes) {
  const Lattice l = lattice(8);
  const LinearSolver amg = expect_same_solution(elastic_system(l, 1e-3), l.positions);
  EXPECT_EQ(amg.krylov_solves(), 1);
  EXPECT_GT(amg.krylov_iterations(), 1) << "a Krylov method, not a direct solve in disguise";
  EXPECT_NE(amg.preconditioner_description().find("GAMG"), std::string::npos)
      << amg.preconditioner_description();
  EXPECT_NE(amg.preconditioner_description().find("rigid-body"), std::string::npos);
  EXPECT_NE(amg.preconditioner_description().find("SOR on the finest level"), std::string::npos)
      << amg.preconditioner_description();
}

TEST(PetscGamg, TheSystemShallSolveContactMultiplierRowsWithASchurFieldSplit) {
  const Lattice l = lattice(8);
  std::vector<int> bottom;  // the face z = 0 held by multipliers, as active contacts would
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) bottom.push_back(l.node(i, j, 0));
  const LinearSolver amg = expect_same_solution(elastic_system(l, 1e-3, bottom), l.positions);
  EXPECT_NE(amg.preconditioner_description().find("Schur"), std::string::npos)
      << amg.preconditioner_description();
  EXPECT_NE(amg.preconditioner_description().find("64 contact unknowns"), std::string::npos);
  EXPECT_NE(amg.preconditioner_description().find("SOR on the finest level"), std::string::npos)
      << amg.preconditioner_description();
}

TEST(PetscGamg, KrylovIterationsShallStayBelow50AtTwoSizesAFactor8Apart) {
  for (int n : {8, 16}) {
    const Lattice l = lattice(n);
    const LinearSolver amg = expect_same_solution(elastic_system(l, 1e-3), l.positions);
    EXPECT_LE(amg.krylov_max_iterations(), 50) << n * n * n << " nodes: " << amg.preconditioner_description();
    std::printf("[ info ] %d nodes: %d GMRES iterations; %s\n", n * n * n, amg.krylov_max_iterations(),
                amg.preconditioner_description().c_str());
  }
}

TEST(PetscGamg, RefactorisingWithTheSamePatternUsesTheNewValues) {
  const Lattice l = lattice(6);
  BlockPattern A = elastic_system(l, 1e-3);
  LinearSolver amg = tight_amg(l.positions);
  ASSERT_TRUE(amg.factorize(A));
  for (int i = 0; i < A.matrix().rows(); ++i) A.add_diagonal(i, 1.0);  // same pattern, new values
  ASSERT_TRUE(amg.factorize(A));
  const Eigen::VectorXd b = rhs(A.matrix().rows());
  EXPECT_LT((A.matrix() * amg.solve(b) - b).norm(), 1e-9 * b.norm());
  EXPECT_EQ(amg.factorizations(), 2);
}

// The preconditioner of the last setup serves new values of the same pattern while GMRES converges
// about as fast as right after the setup (petsc_amg_solver.cpp): the solve still uses the new matrix.
TEST(PetscGamg, NewValuesOfTheSamePatternReuseTheLastPreconditionerAndSolveTheNewSystem) {
  const Lattice l = lattice(6);
  BlockPattern A = elastic_system(l, 1e-3);
  LinearSolver amg = tight_amg(l.positions);
  const Eigen::VectorXd b = rhs(A.matrix().rows());
  ASSERT_TRUE(amg.factorize(A));
  amg.solve(b);
  for (int i = 0; i < A.matrix().rows(); ++i) A.add_diagonal(i, 1e-4);  // same pattern, slightly new values
  ASSERT_TRUE(amg.factorize(A));
  EXPECT_LT((A.matrix() * amg.solve(b) - b).norm(), 1e-9 * b.norm());
  EXPECT_NE(amg.preconditioner_description().find("reused for 1 more"), std::string::npos)
      << amg.preconditioner_description();
}

TEST(PetscGamg, ByDefaultASolveStopsAtARelativeResidualOf1e4) {
  const Lattice l = lattice(8);
  const BlockPattern A = elastic_system(l, 1e-3);
  const Eigen::VectorXd b = rhs(A.matrix().rows());
  LinearSolver amg(LinearMethod::petsc_gamg);
  amg.set_coordinates(l.positions);
  ASSERT_TRUE(amg.factorize(A));
  const double residual = (A.matrix() * amg.solve(b) - b).norm() / b.norm();
  EXPECT_LT(residual, amg_default_tolerance);
  EXPECT_GT(residual, 1e-10) << "an inexact solve: Newton corrects the rest";
  EXPECT_NE(amg.preconditioner_description().find("rtol 1e-04"), std::string::npos)
      << amg.preconditioner_description();
}

}  // namespace
}  // namespace stoss::solve
