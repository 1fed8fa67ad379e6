// newton_solve: each of its rules (quadratic convergence, factorisation reuse, backtracking, stagnation at
// round-off, failure messages) on small hand-made systems, each test failing when its rule breaks.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/solve/newton.hpp"

namespace stoss::solve {
namespace {

using Vector = Eigen::VectorXd;
using Matrix = Eigen::MatrixXd;

/// R(z) and ∂R/∂z given as functions, on one dense block over every unknown (the pattern built once, as
/// the integrator builds its own before Newton runs). Counts the Jacobians Newton asks for.
class TestSystem : public NonlinearSystem {
 public:
  using Residual = std::function<Vector(const Vector&)>;
  using Jacobian = std::function<Matrix(const Vector&)>;

  TestSystem(int n, Residual residual, Jacobian jacobian)
      : n_(n), residual_(std::move(residual)), jacobian_(std::move(jacobian)) {
    rebuild_pattern();
  }

  void evaluate(const Vector& z, Vector& R, BlockPattern* A) override {
    R = residual_(z);
    if (!A) return;
    ++jacobians;
    A->zero();
    A->scatter(block_, jacobian_(z));
  }
  double residual_measure(const Vector& R) const override { return R.norm(); }
  double increment_measure(const Vector& dz) const override { return dz.norm(); }

  /// A new pattern generation, as when contact adds unknowns: a factorisation of the old one is stale.
  void rebuild_pattern() {
    std::vector<int> dofs(n_);
    for (int i = 0; i < n_; ++i) dofs[i] = i;
    pattern.clear();
    block_ = pattern.add_block(dofs);
    pattern.build(n_);
  }

  BlockPattern pattern;
  int jacobians = 0;  ///< evaluate() calls with A != nullptr

 private:
  int n_;
  Residual residual_;
  Jacobian jacobian_;
  int block_ = -1;
};

/// Every line Newton logs.
struct LogLines {
  std::vector<std::string> lines;
  std::function<void(const std::string&)> sink() {
    return [this](const std::string& line) { lines.push_back(line); };
  }
  int containing(const std::string& text) const {
    return static_cast<int>(std::count_if(lines.begin(), lines.end(),
                                          [&](const std::string& l) { return l.find(text) != l.npos; }));
  }
};

NewtonOptions fresh_every_iteration() {
  NewtonOptions o;
  o.reuse_factorization = false;
  return o;
}

Matrix stiffness() {
  Matrix K(3, 3);
  K << 4, 1, 0, 1, 3, 1, 0, 1, 2;
  return K;
}

/// R(z) = K z + c z³ (componentwise) − f: smooth, monotone, nonlinear in proportion to c; f changeable
/// between calls, as the load of successive steps.
struct CubicSystem {
  CubicSystem(double c, Vector f) : c(c), f(std::move(f)) {}
  CubicSystem(const CubicSystem&) = delete;  // the lambdas hold `this`
  double c;
  Vector f;
  TestSystem system{
      3, [this](const Vector& z) -> Vector { return stiffness() * z + c * z.array().cube().matrix() - f; },
      [this](const Vector& z) -> Matrix {
        return stiffness() + Matrix((3 * c * z.array().square()).matrix().asDiagonal());
      }};
};

/// R(z) = s K z − f with s and f changeable between calls: a linear "step" whose matrix drifts.
struct DriftingLinearSystem {
  DriftingLinearSystem() = default;
  DriftingLinearSystem(const DriftingLinearSystem&) = delete;  // the lambdas hold `this`
  double s = 1;
  Vector f = Vector::LinSpaced(3, 1, 3);
  TestSystem system{3, [this](const Vector& z) -> Vector { return s * stiffness() * z - f; },
                    [this](const Vector&) -> Matrix { return s * stiffness(); }};
};

/// R(z) = exp(z) − 1: Newton from far left overshoots to a huge finite residual.
TestSystem exponential_system() {
  return TestSystem(
      1, [](const Vector& z) -> Vector { return (z.array().exp() - 1).matrix(); },
      [](const Vector& z) -> Matrix { return z.array().exp().matrix().asDiagonal(); });
}

/// R(z) = log(z): Newton from z > e steps to z < 0, where the residual is NaN.
TestSystem logarithm_system() {
  return TestSystem(
      1, [](const Vector& z) -> Vector { return z.array().log().matrix(); },
      [](const Vector& z) -> Matrix { return z.array().inverse().matrix().asDiagonal(); });
}

/// A deterministic value in [-1, 1] from the bits of x (splitmix64): noise a Jacobian cannot see.
double hash_noise(double x) {
  std::uint64_t h = std::bit_cast<std::uint64_t>(x) + 0x9e3779b97f4a7c15ull;
  h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ull;
  h = (h ^ (h >> 27)) * 0x94d049bb133111ebull;
  h ^= h >> 31;
  return 2.0 * static_cast<double>(h >> 11) * 0x1.0p-53 - 1.0;
}

/// R(z) = J (z − 1) + floor · noise(z) with the Jacobian J alone: no Newton step removes the noise, so the
/// residual stays of the order of `floor`, while the increment R / J is of the order of `floor` / J (J
/// stiff, as forces over displacements are).
constexpr double stiff = 1e5;
TestSystem residual_with_floor(double floor) {
  return TestSystem(
      1,
      [floor](const Vector& z) -> Vector {
        return Vector::Constant(1, stiff * (z[0] - 1) + floor * hash_noise(z[0]));
      },
      [](const Vector&) -> Matrix { return Matrix::Constant(1, 1, stiff); });
}

// --- Quadratic convergence -------------------------------------------------------------------------

TEST(Newton, FreshJacobiansConvergeQuadratically) {
  CubicSystem cubic(1.0, Vector::LinSpaced(3, 3, 9));
  TestSystem& system = cubic.system;
  LinearSolver solver;
  Vector z = Vector::Zero(3);
  const NewtonResult result = newton_solve(system, z, system.pattern, solver, fresh_every_iteration());
  ASSERT_TRUE(result.converged) << result.failure << ": " << format_history(result.residuals);
  EXPECT_LE(result.iterations, 8) << format_history(result.residuals);
  EXPECT_EQ(system.jacobians, result.iterations);
  // In the terminal phase r_{k+1} ≤ C r_k²; a stale Jacobian would give r_{k+1} ≈ q r_k (linear).
  int terminal_pairs = 0;
  for (size_t k = 0; k + 1 < result.residuals.size(); ++k) {
    const double r = result.residuals[k], next = result.residuals[k + 1];
    if (r > 1e-2 || next < 1e-14) continue;  // not yet terminal, or at round-off
    ++terminal_pairs;
    EXPECT_LE(next, 10 * r * r) << "step " << k << ": " << format_history(result.residuals);
  }
  EXPECT_GE(terminal_pairs, 1) << "no step in the quadratic phase to check: "
                               << format_history(result.residuals);
}

// --- Factorisation reuse ---------------------------------------------------------------------------

TEST(Newton, ReuseSolvesAMildlyNonlinearSystemWithFewerJacobiansThanIterations) {
  CubicSystem cubic(0.05, Vector::LinSpaced(3, 1, 3));
  TestSystem& system = cubic.system;
  LinearSolver solver;
  Vector z = Vector::Zero(3);
  const NewtonResult result = newton_solve(system, z, system.pattern, solver, NewtonOptions{});
  ASSERT_TRUE(result.converged) << result.failure;
  EXPECT_GE(system.jacobians, 1);
  EXPECT_LT(system.jacobians, result.iterations) << format_history(result.residuals);
  EXPECT_EQ(solver.factorizations(), system.jacobians);
  Vector R;
  system.evaluate(z, R, nullptr);
  EXPECT_LE(system.residual_measure(R), NewtonOptions{}.tolerance);
}

TEST(Newton, WithoutReuseEveryIterationEvaluatesAJacobian) {
  CubicSystem cubic(0.05, Vector::LinSpaced(3, 1, 3));
  TestSystem& system = cubic.system;
  LinearSolver solver;
  Vector z = Vector::Zero(3);
  const NewtonResult result = newton_solve(system, z, system.pattern, solver, fresh_every_iteration());
  ASSERT_TRUE(result.converged) << result.failure;
  EXPECT_GE(result.iterations, 2);
  EXPECT_EQ(system.jacobians, result.iterations);
  EXPECT_EQ(solver.factorizations(), result.iterations);
}

TEST(Newton, ASecondCallReusesTheFactorisationOfTheFirst) {
  CubicSystem cubic(0.05, Vector::LinSpaced(3, 1, 3));
  TestSystem& system = cubic.system;
  LinearSolver solver;
  Vector z = Vector::Zero(3);
  ASSERT_TRUE(newton_solve(system, z, system.pattern, solver, NewtonOptions{}).converged);
  ASSERT_TRUE(solver.ready_for(system.pattern));
  const int jacobians_of_first_call = system.jacobians;

  // The next "step": a slightly different load, started from the last solution.
  cubic.f *= 1.01;
  system.jacobians = 0;
  const NewtonResult result = newton_solve(system, z, system.pattern, solver, NewtonOptions{});
  ASSERT_TRUE(result.converged) << result.failure;
  EXPECT_GE(result.iterations, 1);
  EXPECT_EQ(system.jacobians, 0) << "the first call's factorisation still contracts: no new Jacobian";
  EXPECT_EQ(solver.factorizations(), jacobians_of_first_call);
}

TEST(Newton, ANewPatternGenerationForcesAFreshJacobian) {
  CubicSystem cubic(0.05, Vector::LinSpaced(3, 1, 3));
  TestSystem& system = cubic.system;
  LinearSolver solver;
  Vector z = Vector::Zero(3);
  ASSERT_TRUE(newton_solve(system, z, system.pattern, solver, NewtonOptions{}).converged);
  system.rebuild_pattern();
  ASSERT_FALSE(solver.ready_for(system.pattern));
  system.jacobians = 0;
  cubic.f *= 1.01;
  const NewtonResult result = newton_solve(system, z, system.pattern, solver, NewtonOptions{});
  ASSERT_TRUE(result.converged) << result.failure;
  EXPECT_GE(system.jacobians, 1) << "a factorisation of another pattern must not be reused";
}

/// Solves the drifting system once at s = 1, then again at s = `drift` with `options`: the reused LU of
/// K contracts the residual of s K by exactly |1 − s| per iteration. Returns the second call's result.
NewtonResult solve_after_drift(DriftingLinearSystem& d, double drift, const NewtonOptions& options) {
  LinearSolver solver;
  Vector z = Vector::Zero(3);
  EXPECT_TRUE(newton_solve(d.system, z, d.system.pattern, solver, options).converged);
  d.system.jacobians = 0;
  d.s = drift;
  return newton_solve(d.system, z, d.system.pattern, solver, options);
}

TEST(Newton, RefactorisesWhenTheReusedFactorisationContractsLessThanReuseContraction) {
  NewtonOptions options;  // reuse_contraction 0.2
  DriftingLinearSystem d;
  const NewtonResult result = solve_after_drift(d, 1.3, options);  // contraction 0.3 > 0.2
  ASSERT_TRUE(result.converged) << result.failure;
  EXPECT_EQ(d.system.jacobians, 1);
  EXPECT_LE(result.iterations, 4) << format_history(result.residuals);
}

/// The plain chord iteration: a reused factorisation without Broyden's update.
NewtonOptions chord() {
  NewtonOptions o;
  o.broyden_update = false;
  return o;
}

TEST(Newton, KeepsAFactorisationThatContractsByReuseContraction) {
  NewtonOptions options = chord();
  options.reuse_contraction = 0.35;  // the same contraction 0.3 now suffices
  DriftingLinearSystem d;
  const NewtonResult result = solve_after_drift(d, 1.3, options);
  ASSERT_TRUE(result.converged) << result.failure;
  EXPECT_EQ(d.system.jacobians, 0) << format_history(result.residuals);
  EXPECT_GE(result.iterations, 15) << "0.3 per iteration from about 1 to 1e-10";
}

TEST(Newton, RefactorisesWhenTheContractionCannotReachTheToleranceWithinTheBudget) {
  NewtonOptions options = chord();
  options.reuse_contraction = 0.35;
  options.max_iterations = 15;  // 0.3 per iteration needs about 20
  DriftingLinearSystem d;
  const NewtonResult result = solve_after_drift(d, 1.3, options);
  ASSERT_TRUE(result.converged) << result.failure;
  EXPECT_EQ(d.system.jacobians, 1) << format_history(result.residuals);
  EXPECT_LE(result.iterations, 4);
}

TEST(Newton, DiscardsAReusedStepThatDoesNotReduceTheResidual) {
  DriftingLinearSystem d;
  const NewtonResult result = solve_after_drift(d, 2.5, NewtonOptions{});  // the old LU overshoots: ×1.5
  ASSERT_TRUE(result.converged) << result.failure;
  EXPECT_EQ(d.system.jacobians, 1);
  EXPECT_EQ(result.iterations, 2)
      << "the discarded stale step and the fresh one (exact on a linear system: its error estimate is 0)";
  EXPECT_EQ(*std::max_element(result.residuals.begin(), result.residuals.end()), result.residuals.front())
      << "the grown residual was accepted: " << format_history(result.residuals);
}

TEST(Newton, BroydensUpdateMakesAReusedFactorisationConvergeInFewerIterations) {
  // The chord iteration contracts the drifted system by 0.3 per iteration (≥ 15 iterations, the test
  // above); Broyden's update of the same factorisation solves the 3×3 linear system in a few steps
  // (at most 2n for a linear system, Gay 1979), with no new Jacobian.
  NewtonOptions options;
  options.reuse_contraction = 0.35;
  ASSERT_TRUE(options.broyden_update) << "the default";
  DriftingLinearSystem d;
  const NewtonResult result = solve_after_drift(d, 1.3, options);
  ASSERT_TRUE(result.converged) << result.failure;
  EXPECT_EQ(d.system.jacobians, 0) << format_history(result.residuals);
  EXPECT_LE(result.iterations, 8) << format_history(result.residuals);
}

TEST(Newton, BroydensUpdateOnANonlinearSystemNeedsNoMoreIterationsThanTheChord) {
  for (double c : {0.05, 0.2}) {
    SCOPED_TRACE("c = " + std::to_string(c));
    int iterations[2];
    for (bool broyden : {false, true}) {
      CubicSystem cubic(c, Vector::LinSpaced(3, 1, 3));
      LinearSolver solver;
      Vector z = Vector::Zero(3);
      NewtonOptions options;
      options.broyden_update = broyden;
      options.reuse_contraction = 0.5;
      const NewtonResult result = newton_solve(cubic.system, z, cubic.system.pattern, solver, options);
      ASSERT_TRUE(result.converged) << result.failure;
      Vector R;
      cubic.system.evaluate(z, R, nullptr);
      EXPECT_LE(cubic.system.residual_measure(R), options.tolerance);
      iterations[broyden] = result.iterations;
    }
    EXPECT_LE(iterations[1], iterations[0]);
  }
}

TEST(Newton, StopsAtTheFirstIterateWhoseEstimatedErrorMeetsTheTolerance) {
  // Quadratic convergence: once the residual is below the tolerance, the last increment times the
  // residual's contraction estimates the iterate's error; no extra iteration checks the increment.
  CubicSystem cubic(1.0, Vector::LinSpaced(3, 3, 9));
  LinearSolver solver;
  Vector z = Vector::Zero(3);
  const NewtonOptions options = fresh_every_iteration();
  const NewtonResult result = newton_solve(cubic.system, z, cubic.system.pattern, solver, options);
  ASSERT_TRUE(result.converged) << result.failure;
  const auto below = std::count_if(result.residuals.begin(), result.residuals.end(),
                                   [&](double r) { return r <= options.tolerance; });
  EXPECT_EQ(below, 1) << format_history(result.residuals);
}

// --- Backtracking ----------------------------------------------------------------------------------

TEST(Newton, HalvesAStepWhoseResidualIsNotFinite) {
  TestSystem system = logarithm_system();
  LinearSolver solver;
  LogLines log;
  Vector z = Vector::Constant(1, 5.0);  // the full step lands at 5 (1 − log 5) < 0
  const NewtonResult result =
      newton_solve(system, z, system.pattern, solver, fresh_every_iteration(), log.sink());
  ASSERT_TRUE(result.converged) << result.failure;
  EXPECT_EQ(result.backtracks, 1);
  EXPECT_EQ(log.containing("halving it"), 1);
  EXPECT_EQ(log.containing("nan after a full step, halving it (scale 0.500000)"), 1)
      << (log.lines.empty() ? "" : log.lines.front());
  EXPECT_NEAR(z[0], 1.0, 1e-10);
}

TEST(Newton, WithoutBacktracksANonFiniteStepFails) {
  TestSystem system = logarithm_system();
  LinearSolver solver;
  LogLines log;
  NewtonOptions options = fresh_every_iteration();
  options.max_backtracks = 0;
  Vector z = Vector::Constant(1, 5.0);
  const NewtonResult result = newton_solve(system, z, system.pattern, solver, options, log.sink());
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.failure, "residual is not finite");
  EXPECT_EQ(result.backtracks, 0);
  EXPECT_EQ(log.containing("halving it"), 0);
  EXPECT_EQ(z[0], 5.0) << "z is left alone when Newton fails";
}

TEST(Newton, HalvesAStepWhoseResidualGrowsMoreThanMaxResidualGrowth) {
  // From z = −5 the full step goes to z ≈ 142 (residual e^142). Halvings: 68.6, 31.8, 13.4, 4.2 (residual
  // 66 > 10 × 0.99), −0.4 (0.33): five, then Newton converges.
  TestSystem system = exponential_system();
  LinearSolver solver;
  LogLines log;
  Vector z = Vector::Constant(1, -5.0);
  const NewtonResult result =
      newton_solve(system, z, system.pattern, solver, fresh_every_iteration(), log.sink());
  ASSERT_TRUE(result.converged) << result.failure;
  EXPECT_EQ(result.backtracks, 5);
  EXPECT_EQ(log.containing("halving it"), 5);
  EXPECT_EQ(log.containing("(scale 0.031250)"), 1);
  EXPECT_LT(result.residuals.at(1), 10 * result.residuals.at(0)) << "the accepted step grew the residual";
  EXPECT_NEAR(z[0], 0.0, 1e-10);
}

TEST(Newton, BacktracksAtMostMaxBacktracksTimes) {
  TestSystem system = exponential_system();
  LinearSolver solver;
  NewtonOptions options = fresh_every_iteration();
  options.max_backtracks = 3;  // accepts the step at scale 1/8 (z ≈ 13.4) whatever its residual
  Vector z = Vector::Constant(1, -5.0);
  const NewtonResult result = newton_solve(system, z, system.pattern, solver, options);
  EXPECT_EQ(result.backtracks, 3);
  EXPECT_GT(result.residuals.at(1), 1e5);
}

TEST(Newton, ALargeMaxResidualGrowthTakesTheFullStep) {
  TestSystem system = exponential_system();
  LinearSolver solver;
  NewtonOptions options = fresh_every_iteration();
  options.max_residual_growth = 1e100;  // e^142 ≈ 5e61 is "acceptable": from there one unit per iteration
  Vector z = Vector::Constant(1, -5.0);
  const NewtonResult result = newton_solve(system, z, system.pattern, solver, options);
  EXPECT_EQ(result.backtracks, 0);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.failure, "no convergence in 25 iterations");
}

TEST(Newton, LineSearchModeHalvesAnyStepThatGrowsTheResidual) {
  // From z = −2 the full step goes to 4.39 (residual 80 > 10 × 0.86); the half step to 1.19 (residual 2.3)
  // is accepted under growth 10 and refused under growth 1, which halves once more, to −0.40 (0.33).
  TestSystem system = exponential_system();
  LinearSolver solver;
  NewtonOptions loose = fresh_every_iteration(), line_search = fresh_every_iteration();
  loose.max_residual_growth = 10;
  line_search.max_residual_growth = 1;
  Vector z = Vector::Constant(1, -2.0);
  const NewtonResult with_growth_10 = newton_solve(system, z, system.pattern, solver, loose);
  z = Vector::Constant(1, -2.0);
  const NewtonResult with_growth_1 = newton_solve(system, z, system.pattern, solver, line_search);
  ASSERT_TRUE(with_growth_10.converged);
  ASSERT_TRUE(with_growth_1.converged);
  EXPECT_EQ(with_growth_10.backtracks, 1);
  EXPECT_EQ(with_growth_1.backtracks, 2);
  EXPECT_GT(with_growth_10.residuals.at(1), with_growth_10.residuals.at(0));
  for (size_t k = 0; k + 1 < with_growth_1.residuals.size(); ++k)
    EXPECT_LE(with_growth_1.residuals[k + 1], with_growth_1.residuals[k])
        << format_history(with_growth_1.residuals);
}

// --- Stagnation at round-off -----------------------------------------------------------------------

TEST(Newton, AResidualFloorNearTheToleranceIsAcceptedAsStagnation) {
  for (bool reuse : {false, true}) {
    SCOPED_TRACE(reuse ? "reusing factorisations" : "fresh Jacobians");
    const double tolerance = NewtonOptions{}.tolerance;
    TestSystem system = residual_with_floor(30 * tolerance);
    LinearSolver solver;
    LogLines log;
    NewtonOptions options;
    options.reuse_factorization = reuse;
    Vector z = Vector::Constant(1, 1 - 1 / stiff);  // residual ≈ 1
    const NewtonResult result = newton_solve(system, z, system.pattern, solver, options, log.sink());
    ASSERT_TRUE(result.converged) << result.failure << ": " << format_history(result.residuals);
    EXPECT_EQ(log.containing("stagnated"), 1);
    EXPECT_EQ(log.containing("(round-off), accepted"), 1);
    EXPECT_GT(result.residuals.back(), tolerance) << "accepted above the tolerance: the stagnation rule";
    EXPECT_LE(result.residuals.back(), 100 * tolerance);
    EXPECT_NEAR(z[0], 1.0, 1e-12);
  }
}

TEST(Newton, AResidualFloorFarAboveTheToleranceIsNotAccepted) {
  const double tolerance = NewtonOptions{}.tolerance;
  TestSystem system = residual_with_floor(1e4 * tolerance);  // increments stay ≤ 1e-11: only r decides
  LinearSolver solver;
  LogLines log;
  Vector z = Vector::Constant(1, 1 - 1 / stiff);
  const NewtonResult result = newton_solve(system, z, system.pattern, solver, NewtonOptions{}, log.sink());
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.failure, "no convergence in 25 iterations");
  EXPECT_EQ(log.containing("stagnated"), 0);
}

// --- Failure messages and the history format -------------------------------------------------------

TEST(Newton, NoConvergenceNamesMaxIterations) {
  TestSystem system = exponential_system();
  LinearSolver solver;
  NewtonOptions options;
  options.max_iterations = 7;
  Vector z = Vector::Constant(1, 50.0);  // Newton on e^z − 1 from 50 moves about one unit per iteration
  const Vector start = z;
  const NewtonResult result = newton_solve(system, z, system.pattern, solver, options);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.failure, "no convergence in 7 iterations");
  EXPECT_EQ(result.iterations, 7);
  EXPECT_EQ(result.residuals.size(), 8u) << "the predictor's residual and one per iteration";
  EXPECT_EQ(z, start);
}

TEST(Newton, ANonFinitePredictorResidualFailsBeforeAnyJacobian) {
  TestSystem system = logarithm_system();
  LinearSolver solver;
  Vector z = Vector::Constant(1, -1.0);
  const NewtonResult result = newton_solve(system, z, system.pattern, solver, NewtonOptions{});
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.failure, "residual is not finite at the predictor");
  EXPECT_EQ(result.iterations, 0);
  EXPECT_EQ(system.jacobians, 0);
  EXPECT_EQ(result.residuals.size(), 1u);
}

TEST(Newton, ASingularJacobianIsReported) {
  // R = (z0 + z1 − 2, (z0 + z1)² − 4): its Jacobian [[1, 1], [2s, 2s]] has rank 1 everywhere.
  TestSystem system(
      2,
      [](const Vector& z) -> Vector {
        const double s = z[0] + z[1];
        return Eigen::Vector2d(s - 2, s * s - 4);
      },
      [](const Vector& z) -> Matrix {
        const double s = z[0] + z[1];
        Matrix J(2, 2);
        J << 1, 1, 2 * s, 2 * s;
        return J;
      });
  LinearSolver solver;
  Vector z = Eigen::Vector2d(0.5, 0.25);
  const Vector start = z;
  const NewtonResult result = newton_solve(system, z, system.pattern, solver, NewtonOptions{});
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.failure, "singular Jacobian");
  EXPECT_EQ(result.iterations, 0);
  EXPECT_EQ(z, start);
}

TEST(Newton, ConvergedAtThePredictorTakesNoIteration) {
  TestSystem system = exponential_system();
  LinearSolver solver;
  Vector z = Vector::Zero(1);
  const NewtonResult result = newton_solve(system, z, system.pattern, solver, NewtonOptions{});
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_EQ(system.jacobians, 0);
  EXPECT_TRUE(result.failure.empty());
}

TEST(Newton, FormatHistoryPrintsTwoDecimalsInScientificNotationSeparatedBySpaces) {
  EXPECT_EQ(format_history({1.2, 3.4e-5}), "1.20e+00 3.40e-05");
  EXPECT_EQ(format_history({}), "");
  EXPECT_EQ(format_history({12345.678}), "1.23e+04");
  EXPECT_EQ(format_history({0.0, 1e-300}), "0.00e+00 1.00e-300");
}

}  // namespace
}  // namespace stoss::solve
