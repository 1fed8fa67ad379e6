// Contact patch test B5 (docs/theory.md §6.3) with mortar contact (§4.7, (4.81)–(4.84)): the stacked blocks
// of test_contact_patch.cpp (the lower block clamped at its base, gravity with ν = 0, HHT-α with α = −1/3 to
// rest), the pair built as a MortarContactTerm by hand (scenes cannot select mortar yet). Under gravity with
// ν = 0 the exact discrete state is a laterally uniform column whose interface nodes carry p ∫N_j (one
// element through the height, constant strain): consistent loads of the uniform pressure p = ρ g H. Dual
// mortar reproduces them on both sides (D diagonal, Σ_j M_jl = ∫N^m_l), so the scatter of p_j = −λ_j (the
// node's force λ_j D_jj over D_jj, (4.84)) is round-off, where one-pass NTS scatters by 22–25 %
// (test_contact_patch.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/contact/mortar/mortar_term.hpp"
#include "core/fem/assembly.hpp"
#include "core/run/problem.hpp"
#include "core/run/solver_choice.hpp"
#include "core/scene/scene.hpp"
#include "core/time/integrator.hpp"

namespace stoss {
namespace {

using nlohmann::json;

constexpr double density = 1, gravity = 10, upper_height = 0.5;
constexpr double pressure = density * gravity * upper_height;  // p = ρ g H on the interface

json stacked_blocks(int lower, int upper, bool upper_is_slave) {
  const json material = {{"youngs_modulus", 1000}, {"poisson_ratio", 0}, {"density", density}};
  json pair = {{"slave", "upper/bottom"}, {"master", "lower/top"}};
  if (!upper_is_slave) pair = {{"slave", "lower/top"}, {"master", "upper/bottom"}};
  pair["master_surface"] = "faceted";  // mortar integrates on the faceted surface (§4.7)
  return {
      {"format", "stoss-scene/1"},
      {"bodies",
       {{{"name", "lower"},
         {"mesh", {{"box", {{"min", {0, 0, 0}}, {"max", {1, 1, 0.5}}, {"divisions", {lower, lower, 1}}}}}},
         {"material", material}},
        {{"name", "upper"},
         {"mesh",
          {{"box",
            {{"min", {0, 0, 0.5}}, {"max", {1, 1, 0.5 + upper_height}}, {"divisions", {upper, upper, 1}}}}}},
         {"material", material}}}},
      {"contact", json::array({pair})},
      {"boundary", json::array({{{"surface", "lower/bottom"}}})},
      {"gravity", {0, 0, -gravity}},
      {"time", {{"scheme", "hht"}, {"alpha", -1.0 / 3}, {"step", 0.04}, {"end", 16.0}}}};
}

struct MortarPatch {
  double pressure_scatter = 0;  ///< max_j |p_j − p| / p over the active slave nodes
  double total_force = 0;       ///< Σ_j p_j D_jj: the normal contact force the multipliers carry
  double elastic_force = 0;  ///< Σ (f_int − M g)·e_z over the upper block's bottom nodes (its weight at rest)
  double speed = 0;          ///< largest nodal speed at the end
  double penetration = 0;  ///< largest −g̃_j / D_jj of the active nodes
  int active = 0, slave_nodes = 0, newton_iterations = 0;
};

MortarPatch run(int lower, int upper, bool upper_is_slave) {
  const model::Model m = scene::load(stacked_blocks(lower, upper, upper_is_slave));
  run::Problem p = run::build_problem(m);
  const auto scheme = time::make_scheme(m.time);
  auto mortar = std::make_unique<contact::MortarContactTerm>(m.mesh, m.contact.at(0), scheme->force_rule());
  contact::MortarContactTerm& term = *mortar;
  p.contact.at(0) = std::move(mortar);
  time::Integrator integrator(p.mass, p.terms(), p.fixed, time::make_scheme(m.time), run::newton_options(m),
                              p.length_scale, p.total_mass);
  time::State s = run::initial_state(m, p);
  integrator.initialize(s);
  MortarPatch out;
  for (long long k = 0; k < model::step_count(m.time.end, m.time.step); ++k) {
    const solve::NewtonResult r = integrator.step(s, m.time.step);
    EXPECT_TRUE(r.converged) << "step " << k << ": " << r.failure << "; "
                             << solve::format_history(r.residuals);
    if (!r.converged) break;
    out.newton_iterations += r.iterations;
  }
  Eigen::VectorXd p_nodal = Eigen::VectorXd::Zero(m.mesh.node_count()), gap, weight;
  term.contact_pressure(p_nodal);
  term.nodal_gaps(s.x, gap, weight);
  const std::vector<int>& slaves = term.surfaces().slave_nodes;
  out.slave_nodes = static_cast<int>(slaves.size());
  for (size_t j = 0; j < slaves.size(); ++j) {
    if (!term.active()[j]) continue;
    ++out.active;
    out.pressure_scatter = std::max(out.pressure_scatter, std::abs(p_nodal[slaves[j]] - pressure) / pressure);
    out.total_force += p_nodal[slaves[j]] * weight[j];
    out.penetration = std::max(out.penetration, -gap[j] / weight[j]);
  }
  // f_int − M g on the upper block's bottom: the contact force it receives (h = 1, x_n = x: f_int(x)
  // exactly).
  Eigen::VectorXd f = Eigen::VectorXd::Zero(s.x.size()), zero = Eigen::VectorXd::Zero(s.x.size());
  p.elasticity->add(time::StepContext{s.x, zero, 1.0, time::ForceRule::midpoint()}, s.x, f, nullptr);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(s.x.size());
  for (int I = 0; I < m.mesh.node_count(); ++I) g[3 * I + 2] = -gravity;
  f -= p.mass * g;
  for (int I : m.mesh.surface_nodes("upper/bottom")) out.elastic_force += f[3 * I + 2];
  for (int I = 0; I < m.mesh.node_count(); ++I) out.speed = std::max(out.speed, s.v.segment<3>(3 * I).norm());
  std::printf(
      "B5 mortar %d×%d on %d×%d (%s slave): pressure scatter %.2e, total force / load − 1 = %.2e "
      "(multipliers) "
      "%.2e (elastic), max penetration %.1e, speed %.1e, %d of %d slave nodes active, %d Newton iterations\n",
      upper_is_slave ? upper : lower, upper_is_slave ? upper : lower, upper_is_slave ? lower : upper,
      upper_is_slave ? lower : upper, upper_is_slave ? "upper" : "lower", out.pressure_scatter,
      out.total_force / pressure - 1, out.elastic_force / pressure - 1, out.penetration, out.speed,
      out.active, out.slave_nodes, out.newton_iterations);
  return out;
}

void expect_patch_passed(const MortarPatch& r) {
  EXPECT_EQ(r.active, r.slave_nodes);
  EXPECT_LT(r.pressure_scatter, 1e-8);
  EXPECT_NEAR(r.total_force, pressure, 1e-10 * pressure);
  EXPECT_NEAR(r.elastic_force, pressure, 1e-8 * pressure);
  EXPECT_LT(r.penetration, 1e-9);
}

// Newton converges in every step since each clip vertex stays the intersection of its own edges' lines and
// rim edges within 1e-9 of each other count as one line (4.70): before, it stalled at 1e-7 in the first step
// where the slave's rim edges lie on the master's.
TEST(MortarPatch, TwoByTwoOnThreeByThreeTransmitsAUniformPressure) {
  expect_patch_passed(run(3, 2, true));
}

TEST(MortarPatch, ThreeByThreeOnTwoByTwoTransmitsAUniformPressure) {
  expect_patch_passed(run(3, 2, false));
}

TEST(MortarPatch, MatchingMeshesTransmitAUniformPressure) {
  expect_patch_passed(run(3, 3, true));
}

// DISABLED (too slow for CI, run by hand): 16 slave faces against 49 master faces, 400 steps, 181–469 s.
// Measured: scatter 1.5e-10, total force / load − 1 = 8.3e-13, 919 Newton iterations.
TEST(MortarPatch, DISABLED_FourByFourOnSevenBySevenTransmitsAUniformPressure) {
  expect_patch_passed(run(7, 4, true));
}

}  // namespace
}  // namespace stoss
