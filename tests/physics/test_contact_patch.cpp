// Contact patch test B5 (docs/theory.md §6.3): two stacked blocks with non-matching meshes, the lower 3×3×1
// clamped at its base, the upper 2×2×1 its slave, a uniform load, brought to rest. The system shall pass the
// whole load through the interface (total contact force = load to 1e-8) with no penetration beyond the Newton
// tolerance; the scatter of the transmitted pressure is what one-pass NTS cannot remove, and is recorded for
// the faceted and the smooth master surface (docs/smooth_master_surface.md §7).
//
// The load is gravity with ν = 0: then the exact solution of both blocks is a laterally uniform column
// (σ_xx = σ_yy = 0, u_x = u_y = 0), compatible with the clamped base, and the upper block presses on the
// lower one with the uniform pressure p = ρ g H. That state lies in the finite-element space, so any
// scatter is the interface's. Rest: HHT-α with α = −1/3 and a step fifty times the slowest period damps
// every mode by about 1/2 per step (ρ∞ = 1/2); 40 steps leave the static solution.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "../core/recording_observer.hpp"
#include "core/fem/assembly.hpp"
#include "core/fem/saint_venant_kirchhoff.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"

namespace stoss {
namespace {

using nlohmann::json;

constexpr double density = 1, gravity = 10, upper_height = 0.5;
constexpr double pressure = density * gravity * upper_height;  // p = ρ g H on the interface

/// Interface grids: the lower block's top has lower × lower faces, the upper block's bottom upper × upper.
struct Grids {
  int lower = 3, upper = 2;
};

json stacked_blocks(const std::string& master_surface, Grids grids) {
  const json material = {{"youngs_modulus", 1000}, {"poisson_ratio", 0}, {"density", density}};
  return {{"format", "stoss-scene/1"},
          {"bodies",
           {{{"name", "lower"},
             {"mesh",
              {{"box",
                {{"min", {0, 0, 0}}, {"max", {1, 1, 0.5}}, {"divisions", {grids.lower, grids.lower, 1}}}}}},
             {"material", material}},
            {{"name", "upper"},
             {"mesh",
              {{"box",
                {{"min", {0, 0, 0.5}},
                 {"max", {1, 1, 0.5 + upper_height}},
                 {"divisions", {grids.upper, grids.upper, 1}}}}}},
             {"material", material}}}},
          {"contact",
           json::array(
               {{{"slave", "upper/bottom"}, {"master", "lower/top"}, {"master_surface", master_surface}}})},
          {"boundary", json::array({{{"surface", "lower/bottom"}}})},
          {"gravity", {0, 0, -gravity}},
          {"time", {{"scheme", "hht"}, {"alpha", -1.0 / 3}, {"step", 0.04}, {"end", 16.0}}}};
}

/// The force each node of the final state needs from outside the elastic bodies: f_int(x) − M g (the contact
/// force on a slave node, the reaction on a clamped one, 0 on a free node at rest).
Eigen::VectorXd external_force_at_rest(const model::Model& m, const Eigen::VectorXd& x) {
  const auto geometry = fem::precompute_mesh(m.mesh);
  const auto material = std::make_shared<const fem::SaintVenantKirchhoff>(1000, 0);
  fem::ElasticityTerm elasticity(
      m.mesh, geometry, std::vector<std::shared_ptr<const fem::Material>>(m.mesh.element_count(), material));
  Eigen::VectorXd f = Eigen::VectorXd::Zero(x.size()), zero = Eigen::VectorXd::Zero(x.size());
  // h = 1 and x_n = x: the midpoint rule's residual of the elastic term is exactly f_int(x).
  elasticity.add(time::StepContext{x, zero, 1.0, time::ForceRule::midpoint()}, x, f, nullptr);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  for (int I = 0; I < m.mesh.node_count(); ++I) g[3 * I + 2] = -gravity;
  return f - fem::assemble_mass(m.mesh, geometry, std::vector<double>(m.mesh.element_count(), density)) * g;
}

struct PatchResult {
  double total_force = 0;   ///< Σ_I f_I·e_z over the interface nodes of the upper block, f = f_int − M g
  double normal_force = 0;  ///< Σ p_I A_I over the slave nodes: the normal contact forces the run reports
  double free_node_force = 0;   ///< largest |f_int − M g| on the upper block's top nodes (0 at rest)
  double pressure_scatter = 0;  ///< max_I |p_I − p| / p over the slave nodes (reported pressures)
  double force_scatter = 0;  ///< max_I |f_I·e_z / A_I − p| / p over the slave nodes (from the elastic state)
  double top_scatter = 0;    ///< spread of the upper block's top heights over its mean settlement
  double max_penetration = 0;
  double speed = 0;  ///< largest nodal speed at the end
  int slave_nodes = 0;
};

/// Tributary area of a node of a uniform n × n grid of the unit square: a quarter of each face it is on.
double tributary_area(const Eigen::Vector3d& X, int n) {
  const auto on_rim = [](double t) { return std::abs(t) < 1e-12 || std::abs(t - 1) < 1e-12; };
  return 1.0 / (n * n) / (1 << (on_rim(X.x()) + on_rim(X.y())));
}

/// Runs B5 with the given master surface; `upper_is_slave` false swaps the roles (the finer lower top slave).
PatchResult run(const std::string& master_surface, bool upper_is_slave = true, Grids grids = {}) {
  json scene = stacked_blocks(master_surface, grids);
  if (!upper_is_slave) {
    scene["contact"][0]["slave"] = "lower/top";
    scene["contact"][0]["master"] = "upper/bottom";
  }
  const model::Model m = scene::load(scene);
  testing::RecordingObserver r;
  const model::Summary s = simulate(m, r);
  EXPECT_TRUE(s.completed) << master_surface;
  const model::Frame& last = r.frames.back();
  PatchResult out;
  const Eigen::VectorXd f = external_force_at_rest(m, last.position);
  for (int I : m.mesh.surface_nodes("upper/top"))
    out.free_node_force = std::max(out.free_node_force, f.segment<3>(3 * I).norm());
  for (int I : m.mesh.surface_nodes("upper/bottom")) out.total_force += f[3 * I + 2];
  const std::vector<int> slaves = m.mesh.surface_nodes(m.contact.at(0).slave);
  const int n = upper_is_slave ? grids.upper : grids.lower;
  out.slave_nodes = static_cast<int>(slaves.size());
  for (int I : slaves) {
    const double area = tributary_area(m.mesh.nodes[I], n);
    out.normal_force += last.contact_pressure[I] * area;
    out.pressure_scatter =
        std::max(out.pressure_scatter, std::abs(last.contact_pressure[I] - pressure) / pressure);
    out.force_scatter =
        std::max(out.force_scatter, std::abs(std::abs(f[3 * I + 2]) / area - pressure) / pressure);
  }
  double low = 1e300, high = -1e300;
  for (int I : m.mesh.surface_nodes("upper/top")) {
    low = std::min(low, last.position[3 * I + 2]);
    high = std::max(high, last.position[3 * I + 2]);
  }
  out.top_scatter = (high - low) / (1.0 - 0.5 * (high + low));
  out.max_penetration = s.max_penetration;
  for (int I = 0; I < m.mesh.node_count(); ++I)
    out.speed = std::max(out.speed, last.velocity.segment<3>(3 * I).norm());
  std::printf(
      "B5 %d×%d on %d×%d, %-7s slave %-12s total force / load − 1 = %.1e (reported normal forces: %.1e), "
      "largest force on a "
      "free node %.1e, pressure scatter %.2f %% (reported) %.2f %% (elastic), top height spread %.2f %% of "
      "the "
      "settlement, max penetration %.1e, speed at the end %.1e\n",
      grids.upper, grids.upper, grids.lower, grids.lower, master_surface.c_str(),
      m.contact.at(0).slave.c_str(), out.total_force / pressure - 1, out.normal_force / pressure - 1,
      out.free_node_force, 100 * out.pressure_scatter, 100 * out.force_scatter, 100 * out.top_scatter,
      out.max_penetration, out.speed);
  return out;
}

/// The pressure scatter measured when this test was written (docs/theory.md §6.3 B5): one-pass NTS is far
/// from the 2 % a patch test asks for, on either surface. A change here is a change of the interface's
/// force transfer and belongs in the docs.
double recorded_scatter(const std::string& surface, bool upper_is_slave) {
  if (upper_is_slave) return surface == "faceted" ? 0.2533 : 0.2868;
  return surface == "faceted" ? 0.2224 : 0.4937;
}

TEST(ContactPatch, NonMatchingBlocksPassTheWholeLoadWithoutPenetration) {
  for (const char* surface : {"faceted", "smooth"}) {
    const PatchResult b5 = run(surface);
    EXPECT_NEAR(b5.pressure_scatter, recorded_scatter(surface, true), 1e-3) << surface;
    EXPECT_EQ(b5.slave_nodes, 9);
    EXPECT_LT(b5.speed, 1e-8) << surface << ": at rest";
    EXPECT_NEAR(b5.total_force, pressure * 1.0, 1e-8 * pressure) << surface;
    EXPECT_LT(b5.max_penetration, 1e-9) << surface;
    EXPECT_LT(b5.free_node_force, 1e-8 * pressure) << surface << ": in equilibrium";
    EXPECT_NEAR(b5.normal_force, pressure, 1e-4 * pressure)
        << surface << ": the reported forces, normal to a tilted surface";
    EXPECT_NEAR(b5.force_scatter, b5.pressure_scatter, 1e-3) << surface;
  }
}

// The roles swapped (the finer 3 × 3 top of the lower block as slave): no better.
TEST(ContactPatch, WithTheFinerSideAsSlaveTheLoadPassesAndTheScatterStays) {
  for (const char* surface : {"faceted", "smooth"}) {
    const PatchResult b5 = run(surface, false);
    EXPECT_EQ(b5.slave_nodes, 16);
    EXPECT_LT(b5.max_penetration, 1e-9) << surface;
    EXPECT_NEAR(b5.pressure_scatter, recorded_scatter(surface, false), 1e-3) << surface;
    EXPECT_NEAR(b5.total_force, pressure * 1.0, 1e-8 * pressure) << surface;
  }
}

// The control: with matching meshes the faceted surface passes the patch test (the state is exact and
// the test measures the interface only); the smooth one does not, because a slave node's force reaches the
// master nodes through the spline weights (1/6, 4/6, 1/6 per direction), which are not the consistent
// loads of a uniform pressure next to the rim (docs/smooth_master_surface.md §7).
TEST(ContactPatch, MatchingMeshesPassOnTheFacetedSurfaceOnly) {
  const PatchResult faceted = run("faceted", true, {3, 3});
  EXPECT_LT(faceted.pressure_scatter, 1e-8);
  const PatchResult smooth = run("smooth", true, {3, 3});
  EXPECT_NEAR(smooth.pressure_scatter, 0.2758, 2e-3);
  EXPECT_NEAR(smooth.total_force, pressure, 1e-8 * pressure);
}

}  // namespace
}  // namespace stoss
