// simulate() on small hand-built models: conservation per scheme, loads, supports, cancel, failure.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "core/mesh/generators.hpp"
#include "core/run/solver_choice.hpp"
#include "core/simulate.hpp"
#include "tests/core/recording_observer.hpp"

namespace stoss {
namespace {

using testing::RecordingObserver;

/// docs/theory.md §6.3 B4: a jittered 2×1×1 bar, E = 100, ν = 0.3, ρ = 1, tumbling with ω = (1, 2, 4)
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

double momentum_error(const RecordingObserver& r, const std::string& name) {
  double worst = 0, scale = 0;
  for (int k = 0; k < 3; ++k) scale = std::max(scale, std::abs(r.series(name, k).front()));
  for (int k = 0; k < 3; ++k) worst = std::max(worst, testing::max_drift(r.series(name, k), scale));
  return worst;
}

TEST(Simulate, EnergyMomentumConservesEnergyAndMomentaOfATumblingBar) {
  RecordingObserver r;
  const model::Summary s = simulate(tumbling_bar(model::Scheme::energy_momentum, 0.05, 200), r);
  ASSERT_TRUE(s.completed);
  const auto H = r.series("total_energy");
  EXPECT_LT(testing::max_drift(H, H.front()), 1e-10);
  EXPECT_LT(momentum_error(r, "linear_momentum"), 1e-10);
  EXPECT_LT(momentum_error(r, "angular_momentum"), 1e-10);
  EXPECT_GT(testing::max_drift(r.series("strain_energy"), H.front()), 1e-3) << "the bar must deform";
  // Iterations count solves with a reused factorisation too (NewtonOptions::reuse_factorization; a
  // factorisation is kept while it halves the residual, core/simulate.cpp): a wrong tangent would
  // stall the chord iterations and blow this bound (measured: 13.6 with the exact tangent (2.9)).
  EXPECT_LE(s.newton_iterations_per_step, 16.0);
}

TEST(Simulate, MidpointKeepsMomentaButNotEnergy) {
  RecordingObserver em, mp;
  simulate(tumbling_bar(model::Scheme::energy_momentum, 0.05, 200), em);
  simulate(tumbling_bar(model::Scheme::midpoint, 0.05, 200), mp);
  EXPECT_LT(momentum_error(mp, "linear_momentum"), 1e-10);
  EXPECT_LT(momentum_error(mp, "angular_momentum"), 1e-10);
  const auto Hm = mp.series("total_energy"), He = em.series("total_energy");
  EXPECT_GT(testing::max_drift(Hm, Hm.front()), 100 * testing::max_drift(He, He.front()));
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
  EXPECT_FALSE(r.has_series("max_penetration"));
  EXPECT_FALSE(r.has_series("contact_energy_jump"));
  for (const model::Frame& f : r.frames)
    EXPECT_EQ(f.contact_pressure.size(), 0) << "no contact, no pressure field";
  for (int node : m.mesh.surface_nodes("beam/xmin"))
    for (int k = 0; k < 3; ++k) EXPECT_EQ(r.frames.back().position[3 * node + k], m.mesh.nodes[node][k]);
  EXPECT_GT(r.frames.back().position[3 * m.mesh.surface_nodes("beam/xmax")[0] + 2], 0.05)
      << "the free end moves";
}

/// A unit cube (one hex8) dropping at speed 1 onto a plate clamped at its base (gap 0.05).
model::Model cube_onto_clamped_plate(model::Scheme scheme) {
  model::Model m;
  m.mesh.add_body("plate", mesh::box({-1, -1, -0.3}, {1, 1, 0}, {2, 2, 1}));
  m.mesh.add_body("cube", mesh::box({-0.4, -0.3, 0.05}, {0.2, 0.3, 0.65}, {1, 1, 1}));
  model::BodySpec plate, cube;
  plate.name = "plate";
  plate.material = {"saint_venant_kirchhoff", 500, 0.3, 1};
  cube.name = "cube";
  cube.material = {"saint_venant_kirchhoff", 200, 0.3, 1};
  cube.initial_velocity = {0.2, 0, -1};
  m.bodies = {plate, cube};
  m.boundary.push_back({"plate/bottom", {true, true, true}});
  model::ContactPair pair;
  pair.slave = "cube/bottom";
  pair.master = "plate/top";
  m.contact = {pair};
  m.time = {scheme, 0.01, 0.4};
  m.solver.tolerance = 1e-12;
  m.output.every = 5;
  m.effects = model::resolve_effects(m);
  return m;
}

TEST(Simulate, ContactReportsItsSeriesPressureFramesAndBouncesWithoutEnergyLoss) {
  const model::Model m = cube_onto_clamped_plate(model::Scheme::energy_momentum);
  EXPECT_TRUE(m.has_effect(model::effect::contact_frictionless));
  RecordingObserver r;
  const model::Summary s = simulate(m, r);
  ASSERT_TRUE(s.completed);
  ASSERT_TRUE(r.has_series("active_contacts"));
  ASSERT_TRUE(r.has_series("max_penetration"));
  ASSERT_TRUE(r.has_series("contact_energy_jump"));
  const auto active = r.series("active_contacts");
  EXPECT_EQ(*std::max_element(active.begin(), active.end()), 4) << "all four bottom nodes land";
  EXPECT_EQ(active.back(), 0) << "and the cube bounces off";
  const auto H = r.series("total_energy");
  EXPECT_LT(testing::max_drift(H, H.front()), 1e-9) << "persist + clamped plate: a conservative system";
  const auto vz = [&](const model::Frame& f) {
    double v = 0;
    for (int I = m.mesh.bodies[1].node_begin; I < m.mesh.bodies[1].node_end; ++I)
      v += f.velocity[3 * I + 2] / 8;
    return v;
  };
  EXPECT_GT(vz(r.frames.back()), 0.5) << "moving up after the bounce";
  bool pressed = false;
  for (const model::Frame& f : r.frames) {
    ASSERT_EQ(f.contact_pressure.size(), m.mesh.node_count());
    EXPECT_GE(f.contact_pressure.minCoeff(), 0);
    pressed = pressed || f.contact_pressure.maxCoeff() > 0;
  }
  EXPECT_TRUE(pressed);
  EXPECT_LT(s.max_penetration, 1e-9);
  EXPECT_LT(s.max_own_face_penetration, 1e-9);
}

TEST(Simulate, MidpointContactRunsTheSameBounce) {
  RecordingObserver r;
  ASSERT_TRUE(simulate(cube_onto_clamped_plate(model::Scheme::midpoint), r).completed);
  const auto active = r.series("active_contacts");
  EXPECT_EQ(*std::max_element(active.begin(), active.end()), 4);
  EXPECT_EQ(active.back(), 0);
}

TEST(Simulate, HhtContactRunsTheSameBounce) {
  model::Model m = cube_onto_clamped_plate(model::Scheme::hht);
  m.time.alpha = -0.05;
  RecordingObserver r;
  const model::Summary s = simulate(m, r);
  ASSERT_TRUE(s.completed);
  const auto active = r.series("active_contacts");
  EXPECT_EQ(*std::max_element(active.begin(), active.end()), 4) << "all four bottom nodes land";
  EXPECT_EQ(active.back(), 0) << "and the cube bounces off";
  EXPECT_LT(s.max_own_face_penetration, 1e-9) << "the constraint holds at t_{n+1} (2.11)";
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

namespace stoss {
namespace {

void expect_parts_within_wall(const model::Summary& s) {
  for (double part : {s.assembly_seconds, s.contact_seconds, s.linear_solver_seconds, s.output_seconds})
    EXPECT_GE(part, 0.0);
  // The parts are disjoint intervals inside the run: their sum cannot exceed its wall time (slack for
  // the clock reads themselves).
  EXPECT_LE(s.assembly_seconds + s.contact_seconds + s.linear_solver_seconds + s.output_seconds,
            s.wall_seconds + 1e-3);
  EXPECT_GT(s.assembly_seconds, 0.0) << "elasticity is assembled at every Newton iteration";
  EXPECT_GT(s.linear_solver_seconds, 0.0);
  // The linear solver's time is its factorisations and its solves, and both happened.
  EXPECT_GT(s.linear_factorization_seconds, 0.0);
  EXPECT_GT(s.linear_solve_seconds, 0.0);
  EXPECT_DOUBLE_EQ(s.linear_factorization_seconds + s.linear_solve_seconds, s.linear_solver_seconds);
  EXPECT_GT(s.output_seconds, 0.0) << "every step writes a series row";
}

TEST(Simulate, SummaryReportsPeakResidentMemory) {
  RecordingObserver r;
  const model::Summary s = simulate(tumbling_bar(model::Scheme::energy_momentum, 0.05, 5), r);
  ASSERT_TRUE(s.completed);
  EXPECT_GT(s.peak_memory_bytes, 1e6) << "a process holding a model and an LU uses more than 1 MB";
  EXPECT_LT(s.peak_memory_bytes, 100e9);
}

TEST(Simulate, WallTimeSplitsIntoAssemblyLinearSolverAndOutputWithoutContact) {
  RecordingObserver r;
  const model::Summary s = simulate(tumbling_bar(model::Scheme::energy_momentum, 0.05, 20), r);
  ASSERT_TRUE(s.completed);
  expect_parts_within_wall(s);
  EXPECT_EQ(s.contact_seconds, 0.0) << "no contact term, nothing timed as contact";
}

TEST(Simulate, WallTimeOfAContactRunCountsTheContactTerms) {
  RecordingObserver r;
  const model::Summary s = simulate(cube_onto_clamped_plate(model::Scheme::energy_momentum), r);
  ASSERT_TRUE(s.completed);
  expect_parts_within_wall(s);
  EXPECT_GT(s.contact_seconds, 0.0);
}

}  // namespace
}  // namespace stoss

namespace stoss {
namespace {

/// api/examples/tumbling_sphere.json at 96 hex8 (divisions 4, layers 1), 10 steps of h = 0.01.
model::Model small_tumbling_sphere() {
  model::Model m;
  m.mesh.add_body("ball", mesh::hollow_sphere({0, 0, 1.3}, 1.0, 0.8, 4, 1));
  model::BodySpec b;
  b.name = "ball";
  b.material = {"saint_venant_kirchhoff", 1e4, 0.4, 1};
  b.initial_velocity = {0, 1, -1};
  b.initial_angular_velocity = {2.0 / 3, 4.0 / 3, 4.0 / 3};
  b.center = Eigen::Vector3d(0, 0, 1.3);
  m.bodies.push_back(b);
  m.time = {model::Scheme::energy_momentum, 0.01, 0.1};
  m.solver.tolerance = 1e-12;
  m.output.every = 5;
  m.effects = model::resolve_effects(m);
  return m;
}

/// Runs m with the direct solver and with `linear`; both complete, the Krylov path really ran (no
/// LU fallback), and the last frames agree to `tolerance` in position (100 × in velocity, which
/// carries 1/h). Returns both runs' observers.
std::pair<RecordingObserver, RecordingObserver> expect_the_direct_answer(model::Model m,
                                                                         model::LinearSolver linear,
                                                                         double tolerance) {
  RecordingObserver direct, krylov;
  const model::Summary sd = simulate(m, direct);
  m.solver.linear = linear;
  const model::Summary sk = simulate(m, krylov);
  EXPECT_TRUE(sd.completed);
  EXPECT_TRUE(sk.completed);
  EXPECT_EQ(sd.krylov_iterations_per_solve, 0.0);
  EXPECT_GT(sk.krylov_iterations_per_solve, 1.0)
      << model::to_string(linear) << " really used a Krylov solver";
  EXPECT_EQ(sk.krylov_fallbacks, 0) << model::to_string(linear);
  EXPECT_EQ(direct.frames.size(), krylov.frames.size());
  if (direct.frames.empty() || direct.frames.size() != krylov.frames.size()) return {direct, krylov};
  const model::Frame &fd = direct.frames.back(), &fk = krylov.frames.back();
  EXPECT_LT((fd.position - fk.position).lpNorm<Eigen::Infinity>(), tolerance) << model::to_string(linear);
  EXPECT_LT((fd.velocity - fk.velocity).lpNorm<Eigen::Infinity>(), 100 * tolerance)
      << model::to_string(linear);
  const auto Hd = direct.series("total_energy"), Hk = krylov.series("total_energy");
  EXPECT_LT(std::abs(Hd.back() - Hk.back()), tolerance * std::abs(Hd.front())) << model::to_string(linear);
  return {direct, krylov};
}

bool logged(const RecordingObserver& r, const std::string& text) {
  return std::any_of(r.logs.begin(), r.logs.end(),
                     [&](const std::string& line) { return line.find(text) != std::string::npos; });
}

// solver.linear "auto" (the default) picks the LU below 5,000 elements and PETSc from there on, and
// the log says which and why; with contact the LU up to 30,000 (docs/measurements.md, "Linear solvers with
// contact"). The large model translates rigidly, so the predictor solves its step.
TEST(Simulate, AutoLinearSolverPicksByElementCountAndSaysSo) {
  RecordingObserver small;
  ASSERT_TRUE(simulate(tumbling_bar(model::Scheme::energy_momentum, 0.01, 1), small).completed);
  EXPECT_TRUE(logged(small, "linear solver: auto → direct (UMFPACK LU): 16 elements, petsc_gamg from 5000"));
  model::Model large;
  large.mesh.add_body("block", mesh::box({0, 0, 0}, {28, 21, 24}, {28, 21, 24}));  // 14,112 elements
  model::BodySpec b;
  b.name = "block";
  b.material = {"saint_venant_kirchhoff", 100, 0.3, 1};
  b.initial_velocity = {0.3, -0.2, 0.1};
  large.bodies.push_back(b);
  large.time = {model::Scheme::energy_momentum, 0.01, 0.01};
  large.effects = model::resolve_effects(large);
  RecordingObserver r;
  ASSERT_TRUE(simulate(large, r).completed);
  EXPECT_TRUE(
      logged(r, "linear solver: auto → petsc_gamg (PETSc GMRES + GAMG, rigid-body modes): 14112 elements"));
  model::ContactPair pair;  // what auto asks of contact is only that there is some
  pair.slave = "block/bottom";
  pair.master = "block/top";
  large.contact.push_back(pair);
  EXPECT_EQ(run::linear_method(large), solve::LinearMethod::direct);
  EXPECT_EQ(run::linear_solver_line(large),
            "linear solver: auto → direct (UMFPACK LU): 14112 elements, petsc_gamg from 30000 with contact");
}

// The system shall give the direct solver's answer, to the Newton tolerance, with either Krylov path.
// Both Newton solves stop at increments ≤ 1e-12 of the model size (diagonal ≈ 2); ten steps of such
// differences stay far below 1e-9.
TEST(Simulate, IterativeLinearSolverGivesTheDirectAnswerToTheNewtonTolerance) {
  const auto [direct, iterative] =
      expect_the_direct_answer(small_tumbling_sphere(), model::LinearSolver::iterative, 1e-9);
  EXPECT_GT((direct.frames.back().position - direct.frames.front().position).norm(), 0.1)
      << "the sphere moved";
}

TEST(Simulate, PetscGamgGivesTheDirectAnswerOnTheTumblingSphere) {
  const auto [direct, amg] =
      expect_the_direct_answer(small_tumbling_sphere(), model::LinearSolver::petsc_gamg, 1e-9);
  EXPECT_TRUE(logged(amg, "GAMG")) << "the log names the preconditioner";
}

// Contact steps add the mixed energy–momentum contact unknowns and multipliers (saddle-point rows):
// the Schur field split of the petsc_gamg path solves them.
TEST(Simulate, PetscGamgGivesTheDirectAnswerThroughAContactBounce) {
  const auto [direct, amg] = expect_the_direct_answer(cube_onto_clamped_plate(model::Scheme::energy_momentum),
                                                      model::LinearSolver::petsc_gamg, 1e-9);
  const auto active = amg.series("active_contacts");
  EXPECT_EQ(*std::max_element(active.begin(), active.end()), 4) << "all four bottom nodes land";
  EXPECT_TRUE(logged(amg, "Schur")) << "the last factorisation was a contact step's field split";
}

}  // namespace
}  // namespace stoss
