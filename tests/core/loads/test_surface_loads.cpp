// The surface loads as terms (docs/theory.md §5b.2–§5b.5): the follower pressure's tangent against finite
// differences under every scheme's force rule, the resultants the loads must have, where in the step the
// amplitude is read, the work and impulse a step adds, and the checkpoint record.
#include <gtest/gtest.h>

#include <random>

#include "core/loads/pressure_load.hpp"
#include "core/loads/traction_load.hpp"
#include "core/mesh/generators.hpp"
#include "core/time/generalized_alpha.hpp"
#include "core/time/static_scheme.hpp"

namespace stoss::loads {
namespace {

/// A 2 × 1 × 1 block of two elements, jittered, with positions at t_n and a trial x_1.
struct JitteredBlock {
  mesh::Mesh mesh;
  Eigen::VectorXd X, x_n, v_n, x_1;
  JitteredBlock() {
    mesh.add_body("block", mesh::box({0, 0, 0}, {2, 1, 1}, {2, 1, 1}));
    X = mesh.reference_positions();
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-0.08, 0.08);
    x_n = X;
    x_1 = X;
    for (Eigen::Index i = 0; i < X.size(); ++i) x_n[i] += u(rng), x_1[i] += u(rng);
    v_n = (x_1 - x_n) / 0.1;
  }
  std::vector<mesh::Quad> surface(const std::string& name) const { return mesh.surface("block/" + name); }
  /// Every boundary face: a closed surface.
  std::vector<mesh::Quad> boundary() const {
    std::vector<mesh::Quad> all;
    for (const auto& [name, faces] : mesh.bodies[0].surfaces)
      all.insert(all.end(), faces.begin(), faces.end());
    return all;
  }
};

/// The term's residual at x and, if K is given, its Jacobian (dense).
Eigen::VectorXd residual(time::Term& term, const time::StepContext& step, const Eigen::VectorXd& x,
                         Eigen::MatrixXd* K = nullptr) {
  solve::BlockPattern pattern;
  term.register_blocks(pattern);
  pattern.build(static_cast<int>(x.size()));
  pattern.zero();
  Eigen::VectorXd R = Eigen::VectorXd::Zero(x.size());
  term.add(step, x, R, K ? &pattern : nullptr);
  if (K) *K = Eigen::MatrixXd(pattern.matrix());
  return R;
}

Eigen::Vector3d resultant(const Eigen::VectorXd& f) {
  return f.reshaped(3, f.size() / 3).rowwise().sum();
}

struct NamedRule {
  const char* name;
  time::ForceRule rule;
};

class EachRule : public ::testing::TestWithParam<NamedRule> {};

TEST_P(EachRule, PressureTangentMatchesFiniteDifferences) {
  JitteredBlock b;
  PressureLoad load(b.boundary(), 3.0, Amplitude({{0, 0.5}, {1, 1.5}}), 0.2);
  const time::StepContext step{b.x_n, b.v_n, 0.1, GetParam().rule};
  Eigen::VectorXd z = b.x_n;
  load.begin_step(step, z);
  Eigen::MatrixXd K;
  residual(load, step, b.x_1, &K);
  ASSERT_GT(K.norm(), 0);
  Eigen::MatrixXd fd(K.rows(), K.cols());
  const double eps = 1e-6;
  for (Eigen::Index j = 0; j < b.x_1.size(); ++j) {
    Eigen::VectorXd p = b.x_1, m = b.x_1;
    p[j] += eps;
    m[j] -= eps;
    fd.col(j) = (residual(load, step, p) - residual(load, step, m)) / (2 * eps);
  }
  EXPECT_LT((K - fd).norm(), 1e-8 * K.norm()) << "(5b.3) under " << GetParam().name;
}

TEST_P(EachRule, ADeadTractionHasNoTangentAndTheSameForceEverywhere) {
  JitteredBlock b;
  TractionLoad load(b.surface("top"), b.X, {0.5, -1, 2});
  const time::StepContext step{b.x_n, b.v_n, 0.1, GetParam().rule};
  Eigen::VectorXd z = b.x_n;
  load.begin_step(step, z);
  Eigen::MatrixXd K;
  const Eigen::VectorXd R = residual(load, step, b.x_1, &K);
  EXPECT_EQ(K.norm(), 0);
  EXPECT_LT((residual(load, step, b.X) - R).norm(), 1e-15 * R.norm());
  const Eigen::Vector3d expected = 0.1 * 2.0 * Eigen::Vector3d(0.5, -1, 2);  // h · t · reference area 2
  EXPECT_LT((resultant(R) + expected).norm(), 1e-14 * expected.norm()) << "R holds −h f (5b.2)";
}

INSTANTIATE_TEST_SUITE_P(Rules, EachRule,
                         ::testing::Values(NamedRule{"energy_momentum", time::ForceRule::discrete_gradient()},
                                           NamedRule{"midpoint", time::ForceRule::midpoint()},
                                           NamedRule{"hht", time::GeneralizedAlpha::hht(-0.1).force_rule()},
                                           NamedRule{"generalized_alpha",
                                                     time::GeneralizedAlpha::chung_hulbert(0.6).force_rule()},
                                           NamedRule{"static", time::Static().force_rule()}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(PressureLoad, PushesIntoTheBodyWithPressureTimesArea) {
  JitteredBlock b;
  PressureLoad load(b.surface("top"), 2.5);
  const time::StepContext step{b.X, b.v_n, 1.0, time::ForceRule::end_point(1, 0)};
  const Eigen::Vector3d f = resultant(load.step_force(step, b.X));
  EXPECT_LT((f - Eigen::Vector3d(0, 0, -2.5 * 2.0)).norm(), 1e-14) << "top: area 2, outward normal +z";
}

TEST(PressureLoad, HasNoResultantOnAClosedDeformedSurface) {
  JitteredBlock b;
  PressureLoad load(b.boundary(), 4.0);
  const time::StepContext step{b.x_n, b.v_n, 1.0, time::ForceRule::end_point(1, 0)};
  const Eigen::VectorXd f = load.step_force(step, b.x_1);
  EXPECT_GT(f.norm(), 1.0);
  EXPECT_LT(resultant(f).norm(), 1e-13 * f.norm()) << "∮ n da = 0 for bilinear faces";
}

TEST(PressureLoad, FollowsTheFace) {
  JitteredBlock b;
  PressureLoad load(b.surface("top"), 1.0);
  // Rotate the block by 90° about x: the top's normal +z becomes −y.
  Eigen::VectorXd x = b.X;
  for (Eigen::Index I = 0; I < x.size() / 3; ++I)
    x.segment<3>(3 * I) << b.X[3 * I], -b.X[3 * I + 2], b.X[3 * I + 1];
  const time::StepContext step{x, b.v_n, 1.0, time::ForceRule::end_point(1, 0)};
  EXPECT_LT((resultant(load.step_force(step, x)) - Eigen::Vector3d(0, 2.0, 0)).norm(), 1e-14);
}

TEST(SurfaceLoad, ReadsTheAmplitudeWhereTheRuleEvaluatesTheForce) {
  JitteredBlock b;
  const Eigen::Vector3d t(0, 0, 1);
  const Amplitude ramp({{0, 0}, {1, 1}});
  const double h = 0.5;
  {
    TractionLoad load(b.surface("top"), b.X, t, ramp);
    const time::StepContext em{b.x_n, b.v_n, h, time::ForceRule::discrete_gradient()};
    EXPECT_NEAR(resultant(load.step_force(em, b.x_1))[2], 0.25 * 2.0, 1e-15) << "a(t_n + h/2) (5b.4)";
  }
  {
    TractionLoad load(b.surface("top"), b.X, t, ramp, 0.2);
    const time::ForceRule rule = time::GeneralizedAlpha::hht(-0.1).force_rule();
    const time::StepContext hht{b.x_n, b.v_n, h, rule};
    Eigen::VectorXd z = b.x_n;
    load.begin_step(hht, z);
    const double expected = (rule.weight * 0.7 + rule.previous_weight * 0.2) * 2.0;
    EXPECT_NEAR(resultant(load.step_force(hht, b.x_1))[2], expected, 1e-15) << "w a(t_{n+1}) + w_n a(t_n)";
  }
}

TEST(SurfaceLoad, AStepAddsItsWorkAndImpulseAndAdvancesTheClock) {
  JitteredBlock b;
  PressureLoad load(b.surface("xmax"), 1.5, Amplitude({{0, 1}, {1, 3}}), 0.25);
  const double h = 0.1;
  const time::StepContext step{b.x_n, b.v_n, h, time::ForceRule::discrete_gradient()};
  Eigen::VectorXd z = b.x_n;
  load.begin_step(step, z);
  const Eigen::VectorXd f = load.step_force(step, b.x_1);
  load.end_step(step, b.x_1);
  EXPECT_DOUBLE_EQ(load.work(), f.dot(b.x_1 - b.x_n)) << "(5b.5)";
  EXPECT_LT((load.impulse() - h * resultant(f)).norm(), 1e-15);
  EXPECT_DOUBLE_EQ(load.time(), 0.35);
  // x_m's normal differs from x_n's: the step's force is the one at the midpoint.
  const Eigen::VectorXd x_m = 0.5 * (b.x_n + b.x_1);
  const time::StepContext at_x_m{x_m, b.v_n, 0, time::ForceRule::end_point(1, 0)};
  PressureLoad at_midpoint(b.surface("xmax"), 1.5 * (1 + 2 * 0.3));
  EXPECT_LT((at_midpoint.step_force(at_x_m, x_m) - f).norm(), 1e-14 * f.norm());
}

TEST(SurfaceLoad, ResumesFromItsCheckpointRecord) {
  JitteredBlock b;
  PressureLoad load(b.surface("top"), 2.0, Amplitude({{0, 0}, {1, 1}}));
  const time::StepContext step{b.x_n, b.v_n, 0.2, time::ForceRule::midpoint()};
  load.end_step(step, b.x_1);
  PressureLoad resumed(b.surface("top"), 2.0, Amplitude({{0, 0}, {1, 1}}));
  resumed.restore_state(load.save_state(), b.x_1, b.v_n);
  EXPECT_EQ(resumed.time(), load.time());
  EXPECT_EQ(resumed.work(), load.work());
  EXPECT_EQ(resumed.impulse(), load.impulse());
  time::TermState missing = load.save_state();
  missing.reals.erase("work");
  EXPECT_THROW(
      {
        try {
          resumed.restore_state(missing, b.x_1, b.v_n);
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find("'work' is missing"), std::string::npos) << e.what();
          throw;
        }
      },
      std::invalid_argument);
}

TEST(SurfaceLoad, RefusesANonFiniteLoad) {
  JitteredBlock b;
  EXPECT_THROW(PressureLoad(b.surface("top"), std::nan("")), std::invalid_argument);
  EXPECT_THROW(TractionLoad(b.surface("top"), b.X, {0, INFINITY, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace stoss::loads
