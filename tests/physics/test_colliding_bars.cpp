// The system shall reproduce 1D wave theory for two identical elastic bars colliding end-on
// (docs/theory.md §6.3 B1, api/examples/colliding_bars.json): contact lasts 2L/c, the bars leave with
// exchanged velocities, and energy and momentum are kept.
#include <gtest/gtest.h>

#include <cmath>

#include "../core/recording_observer.hpp"
#include "core/fem/assembly.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"

namespace stoss {
namespace {

using testing::RecordingObserver;

/// Mass-weighted mean z-velocity of a body: Σ_{I∈body} (M v)_I,z / Σ_{I∈body} (M 1)_I,z.
double body_velocity(const model::Model& m, const solve::SparseMatrix& M, const Eigen::VectorXd& v,
                     int body) {
  const Eigen::VectorXd p = M * v, mass = M * Eigen::VectorXd::Ones(v.size());
  double pz = 0, total = 0;
  for (int I = m.mesh.bodies[body].node_begin; I < m.mesh.bodies[body].node_end; ++I) {
    pz += p[3 * I + 2];
    total += mass[3 * I + 2];
  }
  return pz / total;
}

TEST(CollidingBars, ContactLasts2LOverCAndVelocitiesAreExchanged) {
  const model::Model m =
      scene::load_file(std::string(STOSS_SOURCE_DIR) + "/api/examples/colliding_bars.json");
  RecordingObserver r;
  ASSERT_TRUE(simulate(m, r).completed);
  const double h = m.time.step, L = 1, c = std::sqrt(100.0 / 1.0), v0 = 0.1;
  const auto [first, last] = r.contact_window();
  ASSERT_GT(first, 0) << "the bars touch";
  const double duration =
      last - first + h;  // from the start of the first contact step to the end of the last
  EXPECT_NEAR(duration, 2 * L / c, 2 * h) << "prototype: 0.1975 (−1.25 %)";
  EXPECT_NEAR(first, 0.01 / (2 * v0), 2 * h) << "the 0.01 gap closes at relative speed 0.2";
  EXPECT_LT(last, r.rows.back().time - 10 * h) << "separated well before the end";

  std::vector<double> density(m.mesh.element_count(), 1.0);
  const solve::SparseMatrix M = fem::assemble_mass(m.mesh, fem::precompute_mesh(m.mesh), density);
  const Eigen::VectorXd v = r.frames.back().velocity;
  const double left = body_velocity(m, M, v, 0), right = body_velocity(m, M, v, 1);
  EXPECT_NEAR(left, -v0, 0.03 * v0) << "prototype: −0.0985";
  EXPECT_NEAR(right, v0, 0.03 * v0);
  const auto Lz = r.series("linear_momentum", 2);
  const double worst = r.largest_step_change("total_energy");
  EXPECT_LT(worst, 1e-8) << "persist: no energy jump at the impact";
  for (double l : Lz) EXPECT_LT(std::abs(l), 1e-13) << "the total momentum is zero";
  std::printf("B1: contact %.4f–%.4f, duration %.4f (2L/c = %.4f), v = %+.5f / %+.5f, max |ΔH|/H0 %.1e\n",
              first - h, last, duration, 2 * L / c, left, right, worst);
}

}  // namespace
}  // namespace stoss
