// The static scheme (docs/theory.md §5b.6): no inertia rows, no velocities, and equilibrium of a column
// hanging under its own weight against the small-strain answer.
#include <gtest/gtest.h>

#include <cmath>

#include "core/fem/assembly.hpp"
#include "core/fem/saint_venant_kirchhoff.hpp"
#include "core/mesh/generators.hpp"
#include "core/time/integrator.hpp"
#include "core/time/static_scheme.hpp"

namespace stoss::time {
namespace {

TEST(StaticScheme, HasNoInertiaAndNoVelocity) {
  const Static scheme;
  mesh::Mesh m;
  m.add_body("cube", mesh::box({0, 0, 0}, {1, 1, 1}, {1, 1, 1}));
  const solve::SparseMatrix M = fem::assemble_mass(m, fem::precompute_mesh(m), {3.0});
  State s{m.reference_positions(), Eigen::VectorXd::Constant(24, 2.0), Eigen::VectorXd::Constant(24, 1.0)};
  Eigen::VectorXd R = Eigen::VectorXd::Zero(24);
  scheme.add_inertia(s, 0.1, M, s.x + s.v, R);
  EXPECT_EQ(R.norm(), 0);
  EXPECT_EQ(scheme.inertia_jacobian_factor(0.1), 0);
  EXPECT_EQ(scheme.predict(s, 0.1), s.x) << "the step starts from the last equilibrium";
  EXPECT_TRUE(scheme.force_rule().is_end_point());
  EXPECT_EQ(scheme.force_rule().previous_weight, 0);
  const Eigen::VectorXd x_1 = s.x + 0.01 * s.v;
  scheme.advance(s, 0.1, x_1);
  EXPECT_EQ(s.x, x_1);
  EXPECT_EQ(s.v.norm(), 0);
  EXPECT_EQ(s.a.norm(), 0);
}

/// A column [0,1]² × [0, L] held on its top face, hanging in gravity −g e_z, ν = 0 (no lateral coupling).
TEST(StaticScheme, HangingColumnMatchesTheSmallStrainAnswer) {
  const double E = 1e4, rho = 2.0, g = 0.5, L = 3;  // ρ g L / E = 1.5e-4
  mesh::Mesh m;
  m.add_body("column", mesh::box({0, 0, 0}, {1, 1, L}, {1, 1, 6}));
  const auto geometry = fem::precompute_mesh(m);
  const solve::SparseMatrix M = fem::assemble_mass(m, geometry, std::vector<double>(m.hex8.size(), rho));
  auto material = std::make_shared<const fem::SaintVenantKirchhoff>(E, 0.0);
  fem::ElasticityTerm elasticity(m, geometry, std::vector<std::shared_ptr<const fem::Material>>(6, material));
  fem::GravityTerm gravity(M, {0, 0, -g});
  std::vector<char> fixed(M.rows(), 0);
  for (int node : m.surface_nodes("column/top"))
    for (int k = 0; k < 3; ++k) fixed[3 * node + k] = 1;
  solve::NewtonOptions options;
  options.tolerance = 1e-12;
  Integrator integrator(M, {&elasticity, &gravity}, fixed, std::make_unique<Static>(), options,
                        std::sqrt(2 + L * L), M.sum() / 3);
  State s{m.reference_positions(), Eigen::VectorXd::Zero(M.rows()), Eigen::VectorXd::Zero(M.rows())};
  const Eigen::VectorXd X = s.x;
  const solve::NewtonResult first = integrator.step(s, 1.0);
  ASSERT_TRUE(first.converged) << first.failure;
  // u(z) = −ρ g (L² − (L − z)²)/(2E) measured from the held top, at the bottom −ρ g L²/(2E); linear
  // elements with consistent loads are exact at the nodes in 1D, SVK adds a relative O(ρ g L / E).
  const double u_bottom = -rho * g * L * L / (2 * E), strain = rho * g * L / E;
  for (int node = 0; node < 4; ++node)
    EXPECT_NEAR(s.x[3 * node + 2] - X[3 * node + 2], u_bottom, 3 * strain * std::abs(u_bottom));
}

}  // namespace
}  // namespace stoss::time
