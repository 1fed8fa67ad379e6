// The system shall conserve energy (energy_momentum) and both momenta (both schemes) of the free
// tumbling hollow sphere of docs/theory.md §7, api/examples/tumbling_sphere*.json.
#include <gtest/gtest.h>

#include <cmath>

#include "../core/recording_observer.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"

namespace stoss {
namespace {

using testing::max_drift;
using testing::RecordingObserver;

model::Model example(const std::string& name, model::Scheme scheme) {
  model::Model m = scene::load_file(std::string(STOSS_SOURCE_DIR) + "/api/examples/" + name);
  m.time.scheme = scheme;
  return m;
}

struct SchemeRun {
  RecordingObserver r;
  double energy_error = 0, linear_error = 0, angular_error = 0;
  explicit SchemeRun(const model::Model& m) {
    // The midpoint rule is the comparator: on the hard sphere's large step its energy drifts 45 %, past
    // the 1 % of (V3) (docs/results.md "Verdict"), which is what these tests show.
    if (m.time.scheme == model::Scheme::midpoint) r.allow_suspect();
    EXPECT_TRUE(simulate(m, r).completed);
    const auto H = r.series("total_energy");
    energy_error = max_drift(H, std::abs(H.front()));
    linear_error = r.vector_drift("linear_momentum");
    angular_error = r.vector_drift("angular_momentum");
  }
};

class TumblingSphere : public ::testing::TestWithParam<std::string> {};

TEST_P(TumblingSphere, EnergyMomentumConservesEnergyAndMomentaEveryStep) {
  SchemeRun run(example(GetParam(), model::Scheme::energy_momentum));
  EXPECT_LT(run.energy_error, 1e-9);
  EXPECT_LT(run.linear_error, 1e-10);
  EXPECT_LT(run.angular_error, 1e-10);
  EXPECT_GT(max_drift(run.r.series("strain_energy"), run.r.series("total_energy").front()), 1e-6)
      << "the spinning shell must deform, or energy conservation is trivial";
  RecordProperty("energy_error", std::to_string(run.energy_error));
}

/// Compressible neo-Hookean (docs/theory.md §2.6): the discrete stress (2.15) makes the step exact for a
/// non-quadratic energy.
TEST_P(TumblingSphere, NeoHookeanEnergyMomentumConservesEnergyAndMomentaEveryStep) {
  model::Model m = example(GetParam(), model::Scheme::energy_momentum);
  for (model::BodySpec& b : m.bodies) b.material.model = "neo_hookean";
  SchemeRun run(m);
  EXPECT_LT(run.energy_error, 1e-10);
  EXPECT_LT(run.linear_error, 1e-10);
  EXPECT_LT(run.angular_error, 1e-10);
  EXPECT_GT(max_drift(run.r.series("strain_energy"), run.r.series("total_energy").front()), 1e-6);
  std::printf("neo-Hookean energy error on %s: %.3e, momenta %.3e %.3e\n", GetParam().c_str(),
              run.energy_error, run.linear_error, run.angular_error);
}

TEST_P(TumblingSphere, MidpointConservesMomenta) {
  SchemeRun run(example(GetParam(), model::Scheme::midpoint));
  EXPECT_LT(run.linear_error, 1e-10);
  EXPECT_LT(run.angular_error, 1e-10);
  RecordProperty("midpoint_energy_error", std::to_string(run.energy_error));
  std::printf("midpoint energy error on %s: %.3e\n", GetParam().c_str(), run.energy_error);
}

INSTANTIATE_TEST_SUITE_P(Examples, TumblingSphere,
                         ::testing::Values("tumbling_sphere.json", "tumbling_sphere_hard.json"),
                         [](const auto& info) {
                           return info.param == "tumbling_sphere.json" ? "h001" : "h005";
                         });

TEST(TumblingSphereHard, MidpointEnergyErrorExceedsEnergyMomentum) {
  SchemeRun em(example("tumbling_sphere_hard.json", model::Scheme::energy_momentum));
  SchemeRun mp(example("tumbling_sphere_hard.json", model::Scheme::midpoint));
  std::printf("h = 0.05: energy error midpoint %.3e, energy_momentum %.3e\n", mp.energy_error,
              em.energy_error);
  EXPECT_GT(mp.energy_error, 10 * em.energy_error);
}

TEST(TumblingSphere, DiscreteMassMatchesThePrototype) {
  // docs/theory.md §7: the 432-element ball has discrete mass 1.98376 (analytic 2.0441), and the
  // initial momentum is m_b v with v = (0, 1, −1).
  RecordingObserver r;
  model::Model m = example("tumbling_sphere.json", model::Scheme::energy_momentum);
  m.time.end = m.time.step;  // one step is enough
  simulate(m, r);
  EXPECT_NEAR(r.series("linear_momentum", 1).front(), 1.98376, 5e-6);
  EXPECT_NEAR(r.series("linear_momentum", 2).front(), -1.98376, 5e-6);
}

}  // namespace
}  // namespace stoss
