// The time schemes (docs/theory.md §2): each scheme's inertia rows and the elasticity term under its
// force rule against finite differences, the ½ and (1+α) scalings, and generalized-α's defining
// properties on a linear oscillator (spectral radius ρ∞ at infinite frequency, second-order accuracy,
// no dissipation at ρ∞ = 1).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

#include "core/fem/assembly.hpp"
#include "core/fem/neo_hookean.hpp"
#include "core/mesh/generators.hpp"
#include "core/time/generalized_alpha.hpp"
#include "core/time/integrator.hpp"
#include "core/time/scheme.hpp"

namespace stoss::time {
namespace {

model::TimeSpec spec(model::Scheme scheme) {
  model::TimeSpec t;
  t.scheme = scheme;
  t.alpha = -0.1;
  t.rho_infinity = 0.6;
  return t;
}

/// One jittered, neo-Hookean hexahedron moving: x_n, v_n, a trial x_1.
struct OneElement {
  mesh::Mesh mesh;
  std::unique_ptr<fem::ElasticityTerm> term;
  solve::BlockPattern pattern;
  Eigen::VectorXd x_n, v_n, x_1;
  OneElement() {
    mesh.add_body("cube", mesh::box({0, 0, 0}, {1, 1, 1}, {1, 1, 1}));
    auto material = std::make_shared<const fem::NeoHookean>(1e3, 0.3);
    term = std::make_unique<fem::ElasticityTerm>(mesh, fem::precompute_mesh(mesh),
                                                 std::vector<std::shared_ptr<const fem::Material>>{material});
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-0.1, 0.1);
    x_n = mesh.reference_positions();
    v_n = Eigen::VectorXd::Zero(x_n.size());
    for (Eigen::Index i = 0; i < x_n.size(); ++i) x_n[i] += u(rng), v_n[i] = 10 * u(rng);
    x_1 = x_n + 0.05 * v_n;
    term->register_blocks(pattern);
    pattern.build(static_cast<int>(x_n.size()));
  }
  /// h f_alg at x, and its Jacobian if K is given.
  Eigen::VectorXd residual(const StepContext& step, const Eigen::VectorXd& x, Eigen::MatrixXd* K = nullptr) {
    Eigen::VectorXd R = Eigen::VectorXd::Zero(x.size());
    pattern.zero();
    term->add(step, x, R, K ? &pattern : nullptr);
    if (K) *K = Eigen::MatrixXd(pattern.matrix());
    return R;
  }
};

class EachScheme : public ::testing::TestWithParam<model::Scheme> {};

TEST_P(EachScheme, ElasticityUnderTheForceRuleMatchesFiniteDifferences) {
  OneElement o;
  const double h = 0.05;
  const StepContext step{o.x_n, o.v_n, h, make_scheme(spec(GetParam()))->force_rule()};
  Eigen::VectorXd z = o.x_n;
  o.term->begin_step(step, z);
  Eigen::MatrixXd K;
  o.residual(step, o.x_1, &K);
  Eigen::MatrixXd fd(K.rows(), K.cols());
  const double eps = 1e-7;
  for (Eigen::Index j = 0; j < o.x_1.size(); ++j) {
    Eigen::VectorXd p = o.x_1, m = o.x_1;
    p[j] += eps;
    m[j] -= eps;
    fd.col(j) = (o.residual(step, p) - o.residual(step, m)) / (2 * eps);
  }
  EXPECT_LT((K - fd).norm(), 1e-6 * K.norm());
}

TEST_P(EachScheme, InertiaRowsMatchTheirJacobianFactor) {
  OneElement o;
  const double h = 0.05;
  const auto scheme = make_scheme(spec(GetParam()));
  const solve::SparseMatrix M = fem::assemble_mass(o.mesh, fem::precompute_mesh(o.mesh), {2.0});
  State s{o.x_n, o.v_n, 0.3 * o.v_n};
  auto inertia = [&](const Eigen::VectorXd& x) {
    Eigen::VectorXd R = Eigen::VectorXd::Zero(x.size());
    scheme->add_inertia(s, h, M, x, R);
    return R;
  };
  Eigen::VectorXd dx = Eigen::VectorXd::LinSpaced(o.x_1.size(), -1, 1);
  const Eigen::VectorXd fd = (inertia(o.x_1 + 1e-6 * dx) - inertia(o.x_1 - 1e-6 * dx)) / 2e-6;
  const Eigen::VectorXd expected = scheme->inertia_jacobian_factor(h) * (M * dx);
  EXPECT_LT((fd - expected).norm(), 1e-8 * expected.norm());
}

INSTANTIATE_TEST_SUITE_P(Schemes, EachScheme, ::testing::ValuesIn(model::all_schemes),
                         [](const auto& info) { return model::to_string(info.param); });

TEST(ForceRule, MidpointHalvesTheTangentAtTheMidpoint) {
  OneElement o;
  const double h = 0.05;
  const StepContext step{o.x_n, o.v_n, h, ForceRule::midpoint()};
  Eigen::MatrixXd K;
  const Eigen::VectorXd R = o.residual(step, o.x_1, &K);
  const Eigen::VectorXd x_m = 0.5 * (o.x_n + o.x_1);
  const StepContext at_x_m{x_m, o.v_n, h, ForceRule::end_point(1, 0)};
  Eigen::MatrixXd K_m;
  const Eigen::VectorXd R_m = o.residual(at_x_m, x_m, &K_m);
  EXPECT_LT((R - R_m).norm(), 1e-14 * R.norm()) << "h f(x_m) (2.5)";
  EXPECT_LT((K - 0.5 * K_m).norm(), 1e-14 * K.norm()) << "½ h K(x_m) (2.5)";
}

TEST(ForceRule, HhtWeighsTheEndForcesByOnePlusAlphaAndMinusAlpha) {
  OneElement o;
  const double h = 0.05, alpha = -0.1;
  const ForceRule rule = GeneralizedAlpha::hht(alpha).force_rule();
  EXPECT_DOUBLE_EQ(rule.weight, 1 + alpha);
  EXPECT_DOUBLE_EQ(rule.previous_weight, -alpha);
  StepContext step{o.x_n, o.v_n, h, rule};
  Eigen::VectorXd z = o.x_n;
  o.term->begin_step(step, z);
  Eigen::MatrixXd K, K_1;
  const Eigen::VectorXd R = o.residual(step, o.x_1, &K);
  const StepContext plain{o.x_n, o.v_n, h, ForceRule::end_point(1, 0)};
  const Eigen::VectorXd f_1 = o.residual(plain, o.x_1, &K_1), f_n = o.residual(plain, o.x_n);
  EXPECT_LT((R - ((1 + alpha) * f_1 - alpha * f_n)).norm(), 1e-13 * R.norm()) << "h × (2.11)";
  EXPECT_LT((K - (1 + alpha) * K_1).norm(), 1e-13 * K.norm());
}

TEST(GeneralizedAlpha, HhtIsTheMemberWithoutInertiaShift) {
  const GeneralizedAlpha hht = GeneralizedAlpha::hht(-0.1);
  EXPECT_EQ(hht.alpha_m(), 0);
  EXPECT_DOUBLE_EQ(hht.alpha_f(), 0.1);
  EXPECT_DOUBLE_EQ(hht.beta(), 1.1 * 1.1 / 4);
  EXPECT_DOUBLE_EQ(hht.gamma(), 0.6);
  const GeneralizedAlpha trapezoidal = GeneralizedAlpha::chung_hulbert(1);
  EXPECT_DOUBLE_EQ(trapezoidal.alpha_m(), 0.5);
  EXPECT_DOUBLE_EQ(trapezoidal.alpha_f(), 0.5);
  EXPECT_DOUBLE_EQ(trapezoidal.beta(), 0.25);
  EXPECT_DOUBLE_EQ(trapezoidal.gamma(), 0.5);
}

/// One step of a scheme on the linear oscillator x'' = −ω² x (unit mass), solved exactly (the step
/// equation is linear in x_1).
void oscillator_step(const Scheme& scheme, State& s, double h, double omega) {
  solve::SparseMatrix M(1, 1);
  M.insert(0, 0) = 1;
  const ForceRule rule = scheme.force_rule();
  auto residual = [&](double x_1) {
    Eigen::VectorXd R = Eigen::VectorXd::Zero(1), x = Eigen::VectorXd::Constant(1, x_1);
    scheme.add_inertia(s, h, M, x, R);
    return R[0] + h * omega * omega * (rule.weight * x_1 + rule.previous_weight * s.x[0]);
  };
  const double slope = scheme.inertia_jacobian_factor(h) + h * rule.weight * omega * omega;
  scheme.advance(s, h, Eigen::VectorXd::Constant(1, -residual(0) / slope));
}

/// The amplification matrix of one step on (x, h v, h² a), and its spectral radius.
double spectral_radius(const Scheme& scheme, double h, double omega) {
  Eigen::Matrix3d A;
  for (int k = 0; k < 3; ++k) {
    State s{Eigen::VectorXd::Constant(1, k == 0), Eigen::VectorXd::Constant(1, (k == 1) / h),
            Eigen::VectorXd::Constant(1, (k == 2) / (h * h))};
    oscillator_step(scheme, s, h, omega);
    A.col(k) << s.x[0], h * s.v[0], h * h * s.a[0];
  }
  return A.eigenvalues().cwiseAbs().maxCoeff();
}

TEST(GeneralizedAlpha, SpectralRadiusAtInfiniteFrequencyIsRhoInfinity) {
  for (double rho : {0.0, 0.3, 0.6, 0.9}) {
    const GeneralizedAlpha scheme = GeneralizedAlpha::chung_hulbert(rho);
    EXPECT_NEAR(spectral_radius(scheme, 1.0, 1e6), rho, 1e-3) << "ρ∞ = " << rho;
    EXPECT_GT(spectral_radius(scheme, 1.0, 0.01), 0.999) << "little damping at low frequency, ρ∞ = " << rho;
  }
}

/// Error at t = 1 of x'' = −x from x = 1, v = 0, a = −1 with step h.
double oscillator_error(const Scheme& scheme, double h) {
  State s{Eigen::VectorXd::Constant(1, 1), Eigen::VectorXd::Zero(1), Eigen::VectorXd::Constant(1, -1)};
  for (int n = 0; n < static_cast<int>(std::lround(1 / h)); ++n) oscillator_step(scheme, s, h, 1);
  return std::abs(s.x[0] - std::cos(1.0));
}

TEST(GeneralizedAlpha, IsSecondOrderAccurate) {
  const GeneralizedAlpha scheme = GeneralizedAlpha::chung_hulbert(0.6);
  const double ratio = oscillator_error(scheme, 0.02) / oscillator_error(scheme, 0.01);
  EXPECT_GT(ratio, 3.6);
  EXPECT_LT(ratio, 4.4);
}

TEST(GeneralizedAlpha, WithoutHighFrequencyDampingKeepsTheLinearOscillatorsEnergy) {
  const GeneralizedAlpha scheme = GeneralizedAlpha::chung_hulbert(1);
  State s{Eigen::VectorXd::Constant(1, 1), Eigen::VectorXd::Zero(1), Eigen::VectorXd::Constant(1, -4)};
  for (int n = 0; n < 1000; ++n) oscillator_step(scheme, s, 0.3, 2);
  const double energy = 0.5 * s.v[0] * s.v[0] + 0.5 * 4 * s.x[0] * s.x[0];
  EXPECT_NEAR(energy, 2.0, 1e-12);
  const GeneralizedAlpha damped = GeneralizedAlpha::chung_hulbert(0.5);
  State d{Eigen::VectorXd::Constant(1, 1), Eigen::VectorXd::Zero(1), Eigen::VectorXd::Constant(1, -4)};
  for (int n = 0; n < 1000; ++n) oscillator_step(damped, d, 0.3, 2);
  EXPECT_LT(0.5 * d.v[0] * d.v[0] + 2 * d.x[0] * d.x[0], 1.9) << "ρ∞ < 1 dissipates at hω = 0.6";
}

}  // namespace
}  // namespace stoss::time

namespace stoss::time {
namespace {

/// A scheme that puts its own factor on the forces, and a term that records what it is handed.
class DoubledForces : public Scheme {
 public:
  ForceRule force_rule() const override { return ForceRule::midpoint(); }
  double force_factor(double h) const override { return 2 * h; }
  void add_inertia(const State& s, double h, const solve::SparseMatrix& M, const Eigen::VectorXd& x_1,
                   Eigen::VectorXd& R) const override {
    R.head(x_1.size()) += M * ((2.0 / h) * (x_1 - s.x) - 2.0 * s.v);
  }
  double inertia_jacobian_factor(double h) const override { return 2.0 / h; }
  void advance(State& s, double h, const Eigen::VectorXd& x_1) const override {
    s.v = (2.0 / h) * (x_1 - s.x) - s.v;
    s.x = x_1;
  }
};

class RecordingTerm : public Term {
 public:
  std::string name() const override { return "recording"; }
  void register_blocks(solve::BlockPattern&) override {}
  void add(const StepContext& step, const Eigen::VectorXd&, Eigen::VectorXd&,
           solve::BlockPattern*) const override {
    factors.push_back(step.force_factor);
    rules.push_back(step.rule);
  }
  mutable std::vector<double> factors;
  mutable std::vector<ForceRule> rules;
};

TEST(Integrator, HandsTheTermsTheSchemesForceFactorAndRule) {
  OneElement o;
  const solve::SparseMatrix M = fem::assemble_mass(o.mesh, fem::precompute_mesh(o.mesh), {2.0});
  RecordingTerm term;
  Integrator integrator(M, {&term}, std::vector<char>(o.x_n.size(), 0), std::make_unique<DoubledForces>(), {},
                        1.0, 2.0);
  State s{o.x_n, o.v_n, Eigen::VectorXd::Zero(o.x_n.size())};
  ASSERT_TRUE(integrator.step(s, 0.01).converged);
  ASSERT_FALSE(term.factors.empty());
  for (double f : term.factors) EXPECT_DOUBLE_EQ(f, 0.02);
  for (const ForceRule& r : term.rules) EXPECT_TRUE(r.is_midpoint());
  EXPECT_DOUBLE_EQ(make_scheme(spec(model::Scheme::energy_momentum))->force_factor(0.01), 0.01);
}

}  // namespace
}  // namespace stoss::time
