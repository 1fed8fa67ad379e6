// Static load steps (docs/theory.md §5b.6) on homogeneous deformations, which trilinear elements represent
// exactly: a block on rollers pulled on its top face by a dead traction must match St. Venant–Kirchhoff's
// exact uniaxial answer to the Newton tolerance and the small-strain u = σL/E to O(σ/E); a cube under a
// follower pressure must match SVK's exact compression, in Newton iterations that show the tangent (5b.3).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "core/loads/pressure_load.hpp"
#include "core/loads/traction_load.hpp"
#include "core/time/integrator.hpp"
#include "core/time/static_scheme.hpp"
#include "load_test_utils.hpp"

namespace stoss::loads {
namespace {

using test_utils::Block;

/// SVK under uniaxial nominal stress P (lateral stress free): stretches (lateral a, axial b) from
/// F = diag(a, a, b), S_11 = 0, b S_33 = P (docs/theory.md (1.4), P = F S), by Newton on the two equations.
Eigen::Vector2d svk_uniaxial_stretches(double E, double nu, double P) {
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  Eigen::Vector2d s(1, 1);
  auto equations = [&](const Eigen::Vector2d& ab) {
    const double e11 = 0.5 * (ab[0] * ab[0] - 1), e33 = 0.5 * (ab[1] * ab[1] - 1), tr = 2 * e11 + e33;
    return Eigen::Vector2d(lambda * tr + 2 * mu * e11, ab[1] * (lambda * tr + 2 * mu * e33) - P);
  };
  for (int it = 0; it < 50; ++it) {
    Eigen::Matrix2d J;
    for (int k = 0; k < 2; ++k) {
      Eigen::Vector2d d = Eigen::Vector2d::Zero();
      d[k] = 1e-7;
      J.col(k) = (equations(s + d) - equations(s - d)) / 2e-7;
    }
    s -= J.lu().solve(equations(s));
  }
  return s;
}

/// Rollers: xmin holds x, ymin holds y, bottom holds z (no rigid mode left, no lateral constraint).
std::vector<char> rollers(const Block& b) {
  std::vector<char> fixed(b.mass.rows(), 0);
  const std::pair<const char*, int> supports[] = {{"xmin", 0}, {"ymin", 1}, {"bottom", 2}};
  for (const auto& [surface, direction] : supports)
    for (int node : b.mesh.surface_nodes("block/" + std::string(surface))) fixed[3 * node + direction] = 1;
  return fixed;
}

TEST(StaticScheme, BlockUnderADeadTractionMatchesTheUniaxialAnswer) {
  const double E = 200, nu = 0.3, L = 2, sigma = 0.02;  // σ/E = 1e-4
  Block b({1, 1, L}, {2, 2, 4}, E, nu, 7.0);
  TractionLoad traction(b.surface("top"), b.mesh.reference_positions(), {0, 0, sigma},
                        Amplitude({{0, 0}, {1, 1}}));
  solve::NewtonOptions options;
  options.tolerance = 1e-12;
  time::Integrator integrator(b.mass, {b.elasticity.get(), &traction}, rollers(b),
                              std::make_unique<time::Static>(), options, b.length, b.total_mass);
  time::State s{b.mesh.reference_positions(), Eigen::VectorXd::Zero(b.mass.rows()),
                Eigen::VectorXd::Zero(b.mass.rows())};
  const Eigen::VectorXd X = s.x;
  const int top = static_cast<int>(b.mesh.nodes.size()) - 1;  // (1, 1, L): box's last node
  for (int n = 1; n <= 4; ++n) {
    const solve::NewtonResult r = integrator.step(s, 0.25);
    ASSERT_TRUE(r.converged) << "load step " << n << ": " << r.failure;
    EXPECT_EQ(s.v.norm(), 0) << "a static step has no velocity";
    const double load = sigma * 0.25 * n;  // a(t_{n+1}): the end-point rule
    const Eigen::Vector2d ab = svk_uniaxial_stretches(E, nu, load);
    const double u_top = s.x[3 * top + 2] - X[3 * top + 2], u_side = s.x[3 * top] - X[3 * top];
    EXPECT_NEAR(u_top, (ab[1] - 1) * L, 1e-10 * (ab[1] - 1) * L) << "exact SVK at load step " << n;
    EXPECT_NEAR(u_side, ab[0] - 1, 1e-10 * std::abs(ab[0] - 1)) << "lateral contraction at load step " << n;
    // Small strain: u = σL/E and the lateral −ν σ/E, to a relative O(σ/E) (SVK's ε² terms, (1.4)).
    EXPECT_NEAR(u_top, load * L / E, 3 * (load / E) * (load * L / E));
    EXPECT_NEAR(u_side, -nu * load / E, 3 * (load / E) * (nu * load / E));
  }
}

/// A cube under a follower pressure on its three free faces, on rollers on the other three (symmetry
/// planes): the homogeneous compression x = λ X with Cauchy stress −p 1. For SVK, σ = F S Fᵀ / J = S / λ and
/// S = 3κ E with κ = λ_L + 2μ/3 and E = (λ² − 1)/2, so 3κ (λ² − 1) + 2 p λ = 0 (docs/theory.md (1.4)).
TEST(StaticScheme, CubeUnderAFollowerPressureMatchesTheExactCompression) {
  const double E = 100, nu = 0.25, p = 4;  // p/κ ≈ 0.06: large enough that the follower term matters
  Block b({1, 1, 1}, {2, 2, 2}, E, nu, 1.0);
  std::vector<mesh::Quad> free_faces;
  for (const char* name : {"xmax", "ymax", "top"})
    free_faces.insert(free_faces.end(), b.surface(name).begin(), b.surface(name).end());
  PressureLoad pressure(free_faces, p, Amplitude({{0, 0}, {1, 1}}));
  solve::NewtonOptions options;
  options.tolerance = 1e-12;
  options.reuse_factorization = false;  // every iteration a fresh Newton step: its rate shows the tangent
  time::Integrator integrator(b.mass, {b.elasticity.get(), &pressure}, rollers(b),
                              std::make_unique<time::Static>(), options, b.length, b.total_mass);
  time::State s{b.mesh.reference_positions(), Eigen::VectorXd::Zero(b.mass.rows()),
                Eigen::VectorXd::Zero(b.mass.rows())};
  const double lambda_lame = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  const double kappa = lambda_lame + 2 * mu / 3;
  for (int n = 1; n <= 2; ++n) {
    const solve::NewtonResult r = integrator.step(s, 0.5);
    ASSERT_TRUE(r.converged) << "load step " << n << ": " << r.failure;
    EXPECT_LE(r.iterations, 4) << "quadratic convergence: residuals " << solve::format_history(r.residuals);
    const double q = p * 0.5 * n;
    const double stretch = (-2 * q + std::sqrt(4 * q * q + 36 * kappa * kappa)) / (6 * kappa);
    const Eigen::VectorXd X = b.mesh.reference_positions();
    EXPECT_LT((s.x - stretch * X).lpNorm<Eigen::Infinity>(), 1e-10 * (1 - stretch))
        << "x = λ X at load step " << n << ", λ = " << stretch;
  }
}

}  // namespace
}  // namespace stoss::loads
