// simulate() on small hand-built models: conservation per scheme, loads, supports, cancel, failure.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "core/mesh/generators.hpp"
#include "core/simulate.hpp"
#include "recording_observer.hpp"

namespace stoss {
namespace {

using testing::RecordingObserver;

/// formulation.md §6.3 B4: a jittered 2×1×1 bar, E = 100, ν = 0.3, ρ = 1, tumbling with ω = (1, 2, 4)
/// plus a translation and a deformation velocity.
model::Model tumbling_bar(model::Scheme scheme, double h, int steps) {
  model::Model m;
  mesh::BodyMesh bar = mesh::box({0, 0, 0}, {2, 1, 1}, {4, 2, 2});
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.025, 0.025);
  for (auto& p : bar.nodes) p += Eigen::Vector3d(u(rng), u(rng), u(rng));
  m.mesh.add_body("bar", bar);
  model::BodySpec b;
  b.name = "bar";
  b.material = {"saint_venant_kirchhoff", 100, 0.3, 1};
  b.initial_velocity = {0.3, -0.2, 0.1};
  b.initial_angular_velocity = {1, 2, 4};
  m.bodies.push_back(b);
  m.time = {scheme, h, h * steps};
  m.solver.tolerance = 1e-11;
  m.output.every = 10;
  m.effects = model::resolve_effects(m);
  return m;
}

double max_relative_change(const std::vector<double>& s, double scale) {
  double worst = 0;
  for (double v : s) worst = std::max(worst, std::abs(v - s.front()) / scale);
  return worst;
}

double momentum_error(const RecordingObserver& r, const std::string& name) {
  double worst = 0, scale = 0;
  for (int k = 0; k < 3; ++k) scale = std::max(scale, std::abs(r.series(name, k).front()));
  for (int k = 0; k < 3; ++k) worst = std::max(worst, max_relative_change(r.series(name, k), scale));
  return worst;
}

TEST(Simulate, EnergyMomentumConservesEnergyAndMomentaOfATumblingBar) {
  RecordingObserver r;
  const model::Summary s = simulate(tumbling_bar(model::Scheme::energy_momentum, 0.05, 200), r);
  ASSERT_TRUE(s.completed);
  const auto H = r.series("total_energy");
  EXPECT_LT(max_relative_change(H, H.front()), 1e-10);
  EXPECT_LT(momentum_error(r, "linear_momentum"), 1e-10);
  EXPECT_LT(momentum_error(r, "angular_momentum"), 1e-10);
  EXPECT_GT(max_relative_change(r.series("strain_energy"), H.front()), 1e-3) << "the bar must deform";
  // Iterations count solves with a reused factorisation too (NewtonOptions::reuse_factorization):
  // a wrong tangent would stall the chord iterations and blow this bound.
  EXPECT_LE(s.newton_iterations_per_step, 12.0);
}

TEST(Simulate, MidpointKeepsMomentaButNotEnergy) {
  RecordingObserver em, mp;
  simulate(tumbling_bar(model::Scheme::energy_momentum, 0.05, 200), em);
  simulate(tumbling_bar(model::Scheme::midpoint, 0.05, 200), mp);
  EXPECT_LT(momentum_error(mp, "linear_momentum"), 1e-10);
  EXPECT_LT(momentum_error(mp, "angular_momentum"), 1e-10);
  const auto Hm = mp.series("total_energy"), He = em.series("total_energy");
  EXPECT_GT(max_relative_change(Hm, Hm.front()), 100 * max_relative_change(He, He.front()));
}

TEST(Simulate, HhtDissipatesAndConvergesOnTheSameBar) {
  model::Model m = tumbling_bar(model::Scheme::hht, 0.05, 100);
  m.time.alpha = -0.05;
  RecordingObserver r;
  ASSERT_TRUE(simulate(m, r).completed);
  const auto H = r.series("total_energy");
  EXPECT_LT(H.back(), H.front()) << "HHT with α < 0 damps";
  EXPECT_LT(momentum_error(r, "linear_momentum"), 1e-10) << "forces are balanced in every scheme";
}

TEST(Simulate, FreeFallFollowsGravityExactly) {
  // A linear potential is integrated exactly: the centre of mass falls ½ g t² in every scheme.
  for (auto scheme : {model::Scheme::energy_momentum, model::Scheme::midpoint, model::Scheme::hht}) {
    model::Model m;
    m.mesh.add_body("cube", mesh::box({0, 0, 0}, {1, 1, 1}, {1, 1, 1}));
    model::BodySpec b;
    b.name = "cube";
    b.material = {"saint_venant_kirchhoff", 1e3, 0.3, 2};
    m.bodies.push_back(b);
    m.gravity = Eigen::Vector3d(0, 0, -9.81);
    m.time = {scheme, 0.01, 0.5};
    m.effects = model::resolve_effects(m);
    RecordingObserver r;
    simulate(m, r);
    ASSERT_TRUE(r.has_series("potential_energy"));
    const model::Frame& last = r.frames.back();
    double z = 0;
    for (int I = 0; I < 8; ++I) z += last.position[3 * I + 2] / 8;
    EXPECT_NEAR(z, 0.5 - 0.5 * 9.81 * last.time * last.time, 1e-9) << model::to_string(scheme);
  }
}

TEST(Simulate, DirichletNodesStayPutAndSeriesOfAbsentEffectsAreAbsent) {
  model::Model m;
  m.mesh.add_body("beam", mesh::box({0, 0, 0}, {4, 1, 1}, {4, 1, 1}));
  model::BodySpec b;
  b.name = "beam";
  b.material = {"saint_venant_kirchhoff", 1e3, 0.3, 1};
  b.initial_velocity = {0, 0, 1};
  m.bodies.push_back(b);
  m.boundary.push_back({"beam/xmin", {true, true, true}});
  m.time = {model::Scheme::energy_momentum, 0.01, 0.2};
  m.effects = model::resolve_effects(m);
  RecordingObserver r;
  simulate(m, r);
  EXPECT_FALSE(r.has_series("potential_energy"));
  EXPECT_FALSE(r.has_series("active_contacts"));
  for (int node : m.mesh.surface_nodes("beam/xmin"))
    for (int k = 0; k < 3; ++k) EXPECT_EQ(r.frames.back().position[3 * node + k], m.mesh.nodes[node][k]);
  EXPECT_GT(r.frames.back().position[3 * m.mesh.surface_nodes("beam/xmax")[0] + 2], 0.05) << "the free end moves";
}

TEST(Simulate, CancelStopsBeforeTheNextStep) {
  model::Model m = tumbling_bar(model::Scheme::energy_momentum, 0.05, 50);
  CancelFlag cancel{true};
  RecordingObserver r;
  const model::Summary s = simulate(m, r, &cancel);
  EXPECT_FALSE(s.completed);
  EXPECT_EQ(s.steps, 0);
  EXPECT_FALSE(r.summary.completed);
}

TEST(Simulate, AStepThatDoesNotConvergeIsAnErrorWithItsHistory) {
  model::Model m = tumbling_bar(model::Scheme::energy_momentum, 0.05, 10);
  m.solver.max_iterations = 1;
  RecordingObserver r;
  try {
    simulate(m, r);
    FAIL() << "one Newton iteration cannot converge a nonlinear step";
  } catch (const SolverError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("step 1 (t = 0"), std::string::npos) << what;
    EXPECT_NE(what.find("residual history"), std::string::npos) << what;
    EXPECT_NE(what.find("no convergence in 1 iterations"), std::string::npos) << what;
  }
  EXPECT_FALSE(r.summary.completed);
  for (const auto& row : r.rows)
    for (double v : row.values) EXPECT_TRUE(std::isfinite(v));
}

}  // namespace
}  // namespace stoss
