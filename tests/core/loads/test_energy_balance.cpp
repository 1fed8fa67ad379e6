// The energy–momentum step with loads (docs/theory.md §5b.5): on a free block, every step's energy change
// equals the work the loads did in that step, and the change of linear momentum equals their impulse.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/loads/pressure_load.hpp"
#include "core/loads/traction_load.hpp"
#include "core/time/energy_momentum.hpp"
#include "core/time/integrator.hpp"
#include "load_test_utils.hpp"

namespace stoss::loads {
namespace {

using test_utils::Block;

struct LoadedRun {
  std::vector<double> energy, work;  ///< H_n and Σ W up to step n
  std::vector<Eigen::Vector3d> momentum, impulse;
};

/// A free block, pushed by a pressure ramp on xmax and pulled by a traction on top, under energy–momentum.
LoadedRun run_free_block(Block& b, SurfaceLoad& pressure, SurfaceLoad& traction, int steps, double h) {
  solve::NewtonOptions options;
  options.tolerance = 1e-13;
  time::Integrator integrator(b.mass, {b.elasticity.get(), &pressure, &traction},
                              std::vector<char>(b.mass.rows(), 0), std::make_unique<time::EnergyMomentum>(),
                              options, b.length, b.total_mass);
  time::State s{b.mesh.reference_positions(), Eigen::VectorXd::Zero(b.mass.rows()), {}};
  integrator.initialize(s);
  LoadedRun run;
  auto record = [&] {
    run.energy.push_back(b.energy(s.x, s.v));
    run.work.push_back(pressure.work() + traction.work());
    run.momentum.push_back(b.momentum(s.v));
    run.impulse.push_back(pressure.impulse() + traction.impulse());
  };
  record();
  for (int n = 0; n < steps; ++n) {
    const solve::NewtonResult r = integrator.step(s, h);
    EXPECT_TRUE(r.converged) << "step " << n + 1 << ": " << r.failure;
    if (!r.converged) break;
    record();
  }
  return run;
}

TEST(EnergyMomentumWithLoads, EachStepsEnergyChangeIsTheLoadsWork) {
  Block b({1, 1, 1}, {2, 2, 2}, 1e3, 0.3, 1.0);
  PressureLoad pressure(b.surface("xmax"), 40.0, Amplitude({{0, 0}, {0.1, 1}, {0.2, 0.3}}));
  TractionLoad traction(b.surface("top"), b.mesh.reference_positions(), {5, -3, 30},
                        Amplitude({{0, 0}, {0.15, 1}}));
  const int steps = 40;
  const LoadedRun run = run_free_block(b, pressure, traction, steps, 0.01);
  ASSERT_EQ(run.energy.size(), steps + 1u);
  const double max_energy = *std::max_element(run.energy.begin(), run.energy.end());
  ASSERT_GT(max_energy, 1.0) << "the loads put energy in";
  double worst = 0;
  for (int n = 0; n < steps; ++n) {
    const double imbalance = (run.energy[n + 1] - run.energy[n]) - (run.work[n + 1] - run.work[n]);
    worst = std::max(worst, std::abs(imbalance));
  }
  EXPECT_LE(worst, 1e-10 * max_energy) << "|ΔH − W_step| per step (5b.5)";
  EXPECT_LE(std::abs(run.energy.back() - run.energy.front() - run.work.back()), 1e-10 * max_energy);
}

TEST(EnergyMomentumWithLoads, MomentumChangesByTheLoadsImpulse) {
  Block b({1, 1, 1}, {2, 2, 2}, 1e3, 0.3, 1.0);
  const Eigen::Vector3d t(5, -3, 30);
  const Amplitude ramp({{0, 0}, {0.15, 1}});
  // A pressure with no resultant would hide a wrong impulse: here a dead traction does all the pushing.
  PressureLoad none(b.surface("xmax"), 0.0);
  TractionLoad traction(b.surface("top"), b.mesh.reference_positions(), t, ramp);
  const int steps = 30;
  const double h = 0.01;
  const LoadedRun run = run_free_block(b, none, traction, steps, h);
  ASSERT_EQ(run.momentum.size(), steps + 1u);
  // The dead traction's impulse, independently: h Σ_n a(t_{n+½}) t A, A = 1 (5b.4).
  Eigen::Vector3d impulse = Eigen::Vector3d::Zero();
  for (int n = 0; n < steps; ++n) impulse += h * ramp((n + 0.5) * h) * t;
  EXPECT_LT((traction.impulse() - impulse).norm(), 1e-13 * impulse.norm());
  double worst = 0;
  for (int n = 0; n <= steps; ++n) worst = std::max(worst, (run.momentum[n] - run.impulse[n]).norm());
  EXPECT_LE(worst, 1e-10 * impulse.norm()) << "L_n − L_0 = impulse of the load up to step n";
}

}  // namespace
}  // namespace stoss::loads
