// A hard compression case (issue: materials behind one interface): a soft hollow ball (E = 500)
// thrown at a stiff free plate at 10× the seed example's speed and crushed. St. Venant–Kirchhoff,
// whose energy stays bounded as a volume vanishes, turns elements inside out (a Gauss-point Jacobian
// det F ≤ 0) or fails; compressible neo-Hookean (docs/theory.md §2.6) completes with det F > 0 at every
// Gauss point of every step, and its energy–momentum step keeps energy and both momenta of the free
// system. Coarser than the example (ball divisions 4, plate 8 × 8 × 2) and h = 0.01 for the CI budget.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "../core/recording_observer.hpp"
#include "core/fem/assembly.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"
#include "outcomes.hpp"

namespace stoss {
namespace {

using nlohmann::json;
using testing::RecordingObserver;

model::Model crushed_ball(const std::string& material_model, model::Scheme scheme) {
  std::ifstream in(std::string(STOSS_SOURCE_DIR) + "/api/examples/hollow_ball_plate.json");
  json s = json::parse(in);
  s["bodies"][0]["initial_velocity"] = {0, 10, -10};
  s["bodies"][0]["material"]["youngs_modulus"] = 500;
  s["bodies"][0]["mesh"]["hollow_sphere"]["divisions"] = 4;
  s["bodies"][1]["mesh"]["box"]["divisions"] = {8, 8, 2};
  for (json& body : s["bodies"]) body["material"]["model"] = material_model;
  s["time"] = {{"scheme", model::to_string(scheme)}, {"step", 0.01}, {"end", 0.15}};
  s["output"]["every"] = 1;
  return scene::load(s);
}

/// The smallest det F over every Gauss point of every recorded frame.
double min_gauss_point_jacobian(const model::Model& m, const RecordingObserver& r) {
  const std::vector<fem::ElementGeometry> geometry = fem::precompute_mesh(m.mesh);
  double smallest = 1;
  for (const model::Frame& frame : r.frames)
    for (size_t e = 0; e < m.mesh.hex8.size(); ++e) {
      const fem::Matrix83 x = fem::gather(m.mesh.hex8[e], frame.position);
      for (const fem::GaussPoint& gp : geometry[e].gp)
        smallest = std::min(smallest, fem::deformation_gradient(x, gp).determinant());
    }
  return smallest;
}

TEST(CrushedBall, SaintVenantKirchhoffTurnsElementsInsideOut) {
  const model::Model m = crushed_ball("saint_venant_kirchhoff", model::Scheme::energy_momentum);
  RecordingObserver r;
  bool completed = false;
  try {
    completed = simulate(m, r).completed;
  } catch (const std::exception&) {
  }
  const double smallest = min_gauss_point_jacobian(m, r);
  EXPECT_TRUE(!completed || smallest <= 0) << "SVK should fail or invert here; min det F = " << smallest;
  RecordProperty("svk_min_det_F", std::to_string(smallest));
  std::printf("crushed ball, SVK: %s, min det F %.3f\n", completed ? "completed" : "failed", smallest);
}

TEST(CrushedBall, NeoHookeanCompletesWithEveryJacobianPositiveAndConserves) {
  const model::Model m = crushed_ball("neo_hookean", model::Scheme::energy_momentum);
  RecordingObserver r;
  const model::Summary s = simulate(m, r);
  ASSERT_TRUE(s.completed);
  EXPECT_TRUE(r.all_finite());
  const double smallest = min_gauss_point_jacobian(m, r);
  EXPECT_GT(smallest, 0.3) << "every Gauss point keeps a positive volume";
  EXPECT_LT(s.energy_drift, 1e-9);
  EXPECT_LT(s.linear_momentum_drift, 1e-9);
  EXPECT_LT(s.angular_momentum_drift, 1e-9);
  const std::vector<double> V = r.series("strain_energy"), H = r.series("total_energy");
  EXPECT_GT(*std::max_element(V.begin(), V.end()), 0.15 * H.front())
      << "the ball must be crushed, not bounced";
  RecordProperty("neo_hookean_min_det_F", std::to_string(smallest));
  std::printf("crushed ball, neo-Hookean: min det F %.3f, energy %.2e, momenta %.2e, %.1f its/step\n",
              smallest, s.energy_drift, std::max(s.linear_momentum_drift, s.angular_momentum_drift),
              s.newton_iterations_per_step);
}

}  // namespace
}  // namespace stoss
