#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "core/contact/geometry/segment.hpp"
#include "core/contact/geometry/variations.hpp"
#include "core/contact/penalty/penalty_element.hpp"
#include "tests/core/contact/contact_test_utils.hpp"

namespace stoss::contact {
namespace {
using test::fd_jacobian;
using test::fd_step;
using test::relative_error;

constexpr double stiffness = 1e3;  // ε_N = ε_T; gaps ~0.02 and Δξ ~0.03 give t_N ~ t_T ~ 20
constexpr double no_slip = 1e12;   // a friction coefficient that always sticks

/// `at_end`: the static steps' element, evaluated at x_{n+1} (docs/theory.md §5b.6).
PenaltyParameters parameters(NormalRule rule, double friction, bool at_end = false) {
  PenaltyParameters p{stiffness, stiffness, friction, rule};
  p.at_end = at_end;
  return p;
}

/// ‖t‖_m = sqrt(t_α m^{αβ} t_β) at the midpoint metric.
double metric_norm(const Eigen::Vector2d& t, const Eigen::Matrix2d& metric_inv) {
  return std::sqrt(t.dot(metric_inv * t));
}

/// One step on the warped, rotated segment of `random_nts_state`: at x_n the slave sits at gap g_n over
/// ξ_0; at x_{n+1} the master nodes are perturbed and the slave sits at gap g_1 over ξ_0 + Δξ. The
/// history is a random traction in the tangent plane at x_n.
struct Step {
  Vector15 x_n, x_1;
  FrictionHistory history;
  Eigen::Vector2d xi_start;
};

Step random_step(unsigned seed, double g_n, double g_1) {
  const test::NtsState s = test::random_nts_state(seed);
  std::mt19937 rng(seed + 500);
  const Eigen::Vector2d xi0 = Eigen::Vector2d(0.1, -0.2) + test::random_vector<2>(rng, 0.1);
  const Eigen::Vector2d dxi = test::random_vector<2>(rng, 0.03);
  SegmentNodes nodes_1 = s.nodes;
  for (int K = 0; K < 4; ++K) nodes_1.row(K) += test::random_vector<3>(rng, 0.005).transpose();
  const SegmentFrame f_n = segment_frame(s.nodes, xi0), f_1 = segment_frame(nodes_1, xi0 + dxi);
  const Eigen::Vector2d c = test::random_vector<2>(rng, 5.0);
  Step step;
  step.x_n = element_vector(f_n.y + g_n * f_n.normal, s.nodes);
  step.x_1 = element_vector(f_1.y + g_1 * f_1.normal, nodes_1);
  step.history.traction = c[0] * f_n.tau1 + c[1] * f_n.tau2;
  step.xi_start = xi0;
  return step;
}

/// μ with μ p = ratio ‖t^tr‖: ratio > 1 sticks, < 1 slips, with Φ^tr = (1 − ratio)‖t^tr‖ (5.3).
double friction_for(const Step& s, NormalRule rule, double ratio, bool at_end) {
  const PenaltyResult stick =
      penalty_element(s.x_n, s.x_1, s.history, parameters(rule, no_slip, at_end), s.xi_start);
  return ratio * metric_norm(stick.traction, stick.at_m.frame.metric_inv) / -stick.normal_traction;
}

// ------------------------------------------------------------------------------------------------
// Closed contact in stick and in slip, away from the switch (|Φ^tr| = ½‖t^tr‖ or ‖t^tr‖), for both
// normal rules and for static steps' element at x_{n+1} ("end"); "touchdown" (g_n > 0 > g_1) and "release"
// (g_n < 0 < g_1) exercise the quotient of "dd".
struct Case {
  std::string name;
  NormalRule rule;
  double g_n, g_1;
  double ratio;         ///< μ p / ‖t^tr‖
  bool at_end = false;  ///< static steps (§5b.6)
};

const Case cases[] = {
    {"dd_stick", NormalRule::discrete_derivative, -0.02, -0.03, 2.0},
    {"dd_slip", NormalRule::discrete_derivative, -0.02, -0.03, 0.5},
    {"dd_touchdown_stick", NormalRule::discrete_derivative, 0.01, -0.02, 2.0},
    {"dd_touchdown_slip", NormalRule::discrete_derivative, 0.01, -0.02, 0.5},
    {"dd_release_slip", NormalRule::discrete_derivative, -0.02, 0.01, 0.5},
    {"mid_stick", NormalRule::midpoint, -0.02, -0.03, 2.0},
    {"mid_slip", NormalRule::midpoint, -0.02, -0.03, 0.5},
    {"end_stick", NormalRule::discrete_derivative, -0.02, -0.03, 2.0, true},
    {"end_slip", NormalRule::discrete_derivative, -0.02, -0.03, 0.5, true},
    {"end_touchdown_slip", NormalRule::discrete_derivative, 0.01, -0.02, 0.5, true},
};

class ClosedPenaltyElement : public ::testing::TestWithParam<std::tuple<Case, unsigned>> {
 protected:
  void SetUp() override {
    const auto& [c, seed] = GetParam();
    step = random_step(seed, c.g_n, c.g_1);
    p = parameters(c.rule, friction_for(step, c.rule, c.ratio, c.at_end), c.at_end);
    r = at(step.x_1);
    ASSERT_TRUE(r.closed);
    ASSERT_EQ(r.slip, c.ratio < 1);
  }
  PenaltyResult at(const Vector15& x_1) const {
    return penalty_element(step.x_n, x_1, step.history, p, step.xi_start);
  }
  double pressure() const { return -r.normal_traction; }
  const Eigen::Matrix2d& metric_inv() const { return r.at_m.frame.metric_inv; }
  Step step;
  PenaltyParameters p;
  PenaltyResult r;
};

// The analytic tangent against central differences of `force` w.r.t. x_{n+1}; §6.1 bound 1e-6.
TEST_P(ClosedPenaltyElement, TangentMatchesCentralDifferences) {
  const auto force = [&](const Vector15& x) { return at(x).force; };
  EXPECT_LT(relative_error(r.tangent, fd_jacobian(force, step.x_1, fd_step)), 1e-6);
}

// Σ_nodes F = 0 and Σ x_m × F = 0 (§5.1: penalty friction conserves L and J), 1e-12 relative; about x_{n+1}
// for the static steps' element.
TEST_P(ClosedPenaltyElement, ForceHasNoNetForceOrTorqueAtTheMidpoint) {
  const Vector15 x_m = p.at_end ? step.x_1 : Vector15(0.5 * (step.x_n + step.x_1));
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  for (int node = 0; node < 5; ++node) {
    sum += r.force.segment<3>(3 * node);
    torque += x_m.segment<3>(3 * node).cross(r.force.segment<3>(3 * node));
  }
  EXPECT_LT(sum.norm(), 1e-12 * r.force.norm());
  EXPECT_LT(torque.norm(), 1e-12 * r.force.norm() * x_m.norm());
}

// Stick: slip_work and Δξ_p exactly 0; slip: slip_work = μ p ‖Δξ_p‖_m > 0 (§5.2 item 5), 1e-12.
TEST_P(ClosedPenaltyElement, SlipWorkIsTheCoulombWork) {
  if (!r.slip) {
    EXPECT_EQ(r.slip_work, 0.0);
    EXPECT_EQ(r.slip_increment, Eigen::Vector2d::Zero());
    return;
  }
  const double coulomb =
      p.friction * pressure() * std::sqrt(r.slip_increment.dot(r.at_m.frame.metric * r.slip_increment));
  EXPECT_GT(r.slip_work, 0);
  EXPECT_NEAR(r.slip_work, coulomb, 1e-12 * coulomb);
}

// ‖t_{n+1}‖_m ≤ μ|t_N| (1 + 1e-12), with equality (1e-12) in slip (5.3).
TEST_P(ClosedPenaltyElement, TractionStaysInTheCoulombCone) {
  const double norm = metric_norm(r.traction, metric_inv()), cone = p.friction * pressure();
  EXPECT_LE(norm, cone * (1 + 1e-12));
  if (r.slip) {
    EXPECT_NEAR(norm, cone, 1e-12 * cone);
  }
}

// t_{n+1}·Δξ = ΔW_T + t_{n+1}·Δξ_p + |t_{n+1} − t̃_n|²_m/(2ε_T) (§5.2 item 5), midpoint metric, 1e-12.
TEST_P(ClosedPenaltyElement, TangentialWorkSplitsIntoEnergySlipWorkAndDamping) {
  const Eigen::Vector2d dxi = r.at_1.xi - r.at_n.xi;
  const double work = r.traction.dot(dxi);
  const double dW_T =
      r.tangential_energy - tangential_penalty_energy(r.transported_traction, metric_inv(), stiffness);
  const double damping =
      tangential_penalty_energy(r.traction - r.transported_traction, metric_inv(), stiffness);
  const double scale = std::abs(work) + std::abs(dW_T) + r.slip_work + damping;
  EXPECT_NEAR(work, dW_T + r.slip_work + damping, 1e-12 * scale);
  EXPECT_NEAR(r.tangential_energy, tangential_penalty_energy(r.traction, metric_inv(), stiffness), 0);
}

// t_{T,n+1} = t_{n+1,α} m^{αβ} τ_β: tangent to the face at x_m, and its τ-components are t_{n+1} (§5.2 items
// 3, 7).
TEST_P(ClosedPenaltyElement, HistoryIsTheSpatialTraction) {
  const SegmentFrame& f = r.at_m.frame;
  const Eigen::Vector3d& t = r.history_after.traction;
  EXPECT_LT(std::abs(t.dot(f.normal)), 1e-12 * t.norm());
  EXPECT_LT((Eigen::Vector2d(t.dot(f.tau1), t.dot(f.tau2)) - r.traction).norm(), 1e-12 * r.traction.norm());
  EXPECT_LT((r.transported_traction -
             Eigen::Vector2d(step.history.traction.dot(f.tau1), step.history.traction.dot(f.tau2)))
                .norm(),
            1e-14 * step.history.traction.norm());
}

TEST_P(ClosedPenaltyElement, NormalEnergyIsThePenaltyEnergyAtTheEnd) {
  EXPECT_EQ(r.normal_energy, normal_penalty_energy(stiffness, r.at_1.gap));
  EXPECT_LT(r.normal_traction, 0);
}

INSTANTIATE_TEST_SUITE_P(Cases, ClosedPenaltyElement,
                         ::testing::Combine(::testing::ValuesIn(cases), ::testing::Values(1u, 2u, 3u, 4u)),
                         [](const auto& info) {
                           return std::get<0>(info.param).name + "_seed" +
                                  std::to_string(std::get<1>(info.param));
                         });

// ------------------------------------------------------------------------------------------------
// Open contact: zero force, zero tangent, history reset (§5.2 item 7).
TEST(PenaltyElement, OpenContactGivesNothingAndResetsHistory) {
  const Step s = random_step(7, 0.02, 0.01);
  for (const NormalRule rule : {NormalRule::discrete_derivative, NormalRule::midpoint}) {
    const PenaltyResult r = penalty_element(s.x_n, s.x_1, s.history, parameters(rule, 0.3), s.xi_start);
    EXPECT_FALSE(r.closed);
    EXPECT_FALSE(r.slip);
    EXPECT_EQ(r.force, Vector15::Zero());
    EXPECT_EQ(r.tangent, Matrix15::Zero());
    EXPECT_EQ(r.history_after.traction, Eigen::Vector3d::Zero());
    EXPECT_EQ(r.traction, Eigen::Vector2d::Zero());
    EXPECT_EQ(r.normal_traction, 0.0);
    EXPECT_EQ(r.normal_energy, 0.0);
    EXPECT_EQ(r.tangential_energy, 0.0);
    EXPECT_EQ(r.slip_work, 0.0);
  }
}

// "mid" tests g_m only (§5.2 item 2): a node that penetrates at x_{n+1} but not at x_m exerts no force,
// while "dd" closes; the stored W_N(g_{n+1}) is reported either way.
TEST(PenaltyElement, MidpointRuleClosesOnTheMidpointGapOnly) {
  const Step s = random_step(8, 0.03, -0.01);
  const PenaltyResult mid =
      penalty_element(s.x_n, s.x_1, s.history, parameters(NormalRule::midpoint, 0.3), s.xi_start);
  const PenaltyResult dd =
      penalty_element(s.x_n, s.x_1, s.history, parameters(NormalRule::discrete_derivative, 0.3), s.xi_start);
  ASSERT_GT(mid.at_m.gap, 0);
  EXPECT_FALSE(mid.closed);
  EXPECT_EQ(mid.force, Vector15::Zero());
  EXPECT_EQ(mid.normal_energy, normal_penalty_energy(stiffness, mid.at_1.gap));
  EXPECT_GT(mid.normal_energy, 0);
  EXPECT_TRUE(dd.closed);
  EXPECT_LT(dd.normal_traction, 0);
}

// A failed CPP (slave far outside the face) is treated as open.
TEST(PenaltyElement, FailedProjectionIsOpen) {
  Step s = random_step(9, -0.02, -0.03);
  s.x_1.head<3>() += Eigen::Vector3d(40, 40, 0);
  const PenaltyResult r =
      penalty_element(s.x_n, s.x_1, s.history, parameters(NormalRule::discrete_derivative, 0.3), s.xi_start);
  EXPECT_FALSE(r.at_1.converged && r.at_m.converged);
  EXPECT_FALSE(r.closed);
  EXPECT_EQ(r.force, Vector15::Zero());
}

// ------------------------------------------------------------------------------------------------
// (5.4): on a flat, fixed, undeformed master face g_N is affine in x_s, and the "dd" normal force does
// exactly ΔW_N of work. A rotated, translated flat square; the slave moves along n (the full force
// then does ΔW_N: D_α·Δx = 0), or along n and the face (then the normal part t_N N_s·Δx does).
struct FlatStep {
  Vector15 x_n, x_1;
};

FlatStep flat_step(double g_n, double g_1, const Eigen::Vector2d& slide) {
  std::mt19937 rng(11);
  const Eigen::Matrix3d R = test::random_rotation(rng);
  const Eigen::Vector3d shift = test::random_vector<3>(rng);
  SegmentNodes nodes;
  nodes << -0.5, -0.5, 0, 0.5, -0.5, 0, 0.5, 0.5, 0, -0.5, 0.5, 0;
  for (int K = 0; K < 4; ++K) nodes.row(K) = (R * nodes.row(K).transpose() + shift).transpose();
  const Eigen::Vector3d n = R.col(2), in_plane = slide[0] * R.col(0) + slide[1] * R.col(1);
  const Eigen::Vector3d base = R * Eigen::Vector3d(0.1, -0.15, 0) + shift;
  return {element_vector(base + g_n * n, nodes), element_vector(base + in_plane + g_1 * n, nodes)};
}

TEST(PenaltyElement, DiscreteDerivativeNormalWorkIsThePenaltyEnergyChangeOnAFlatFixedFace) {
  FrictionHistory history;
  history.traction = Eigen::Vector3d(3, -2, 1);
  const auto rule = parameters(NormalRule::discrete_derivative, 0.3);
  const double gaps[][2] = {{0.02, -0.03}, {-0.01, -0.04}, {-0.03, 0.01}, {-0.03, -0.01}, {-0.02, -0.0199}};
  // W_N(g_{n+1}) − W_N(g_n) with the gaps the element computed (3.5).
  const auto energy_change = [](const PenaltyResult& r) {
    return normal_penalty_energy(stiffness, r.at_1.gap) - normal_penalty_energy(stiffness, r.at_n.gap);
  };
  for (const auto& g : gaps) {
    const FlatStep normal_only = flat_step(g[0], g[1], Eigen::Vector2d::Zero());
    const PenaltyResult r =
        penalty_element(normal_only.x_n, normal_only.x_1, history, rule, Eigen::Vector2d::Zero());
    ASSERT_TRUE(r.closed);
    const double dW_N = energy_change(r);
    EXPECT_NEAR(r.force.dot(normal_only.x_1 - normal_only.x_n), dW_N, 1e-12 * std::abs(dW_N));

    const FlatStep sliding = flat_step(g[0], g[1], Eigen::Vector2d(0.04, -0.02));
    const PenaltyResult s = penalty_element(sliding.x_n, sliding.x_1, history, rule, Eigen::Vector2d::Zero());
    ASSERT_TRUE(s.closed);
    const double normal_work = s.normal_traction * gap_gradient(s.at_m.frame).dot(sliding.x_1 - sliding.x_n);
    EXPECT_NEAR(normal_work, energy_change(s), 1e-12 * std::abs(energy_change(s)));
  }
}

// "dd" with |g_{n+1} − g_n| < 1e-14 × face size across g = 0 falls back to ε_N min(g_m, 0) (§5.2 item 2).
// An axis-aligned flat face at z = 0, so the gaps are exact.
TEST(PenaltyElement, DiscreteDerivativeFallsBackToTheMidpointGapForADegenerateGapStep) {
  SegmentNodes nodes;
  nodes << -0.5, -0.5, 0, 0.5, -0.5, 0, 0.5, 0.5, 0, -0.5, 0.5, 0;
  const Vector15 x_n = element_vector(Eigen::Vector3d(0.1, 0.2, -4e-15), nodes);
  const Vector15 x_1 = element_vector(Eigen::Vector3d(0.1, 0.2, 5e-16), nodes);
  const PenaltyResult r = penalty_element(x_n, x_1, {}, parameters(NormalRule::discrete_derivative, 0.3),
                                          Eigen::Vector2d::Zero());
  ASSERT_EQ(r.at_n.gap, -4e-15);
  ASSERT_EQ(r.at_1.gap, 5e-16);
  EXPECT_TRUE(r.closed);
  EXPECT_EQ(r.normal_traction, stiffness * r.at_m.gap);
  EXPECT_TRUE(r.force.allFinite() && r.tangent.allFinite());
}

// The seed's "mid" rule does not do ΔW_N at touchdown (§5.3) — the reason "dd" is the default.
TEST(PenaltyElement, MidpointNormalWorkMissesThePenaltyEnergyAtTouchdown) {
  const FlatStep s = flat_step(0.01, -0.03, Eigen::Vector2d::Zero());
  const PenaltyResult r =
      penalty_element(s.x_n, s.x_1, {}, parameters(NormalRule::midpoint, 0.3), Eigen::Vector2d::Zero());
  const double dW_N = normal_penalty_energy(stiffness, -0.03);
  ASSERT_TRUE(r.closed);
  EXPECT_GT(std::abs(r.force.dot(s.x_1 - s.x_n) - dW_N), 0.1 * dW_N);
}

// Static steps (§5b.6): without friction the element's force is ∂W_N/∂x at x_{n+1}, whatever x_n, so a
// converged load step is the equilibrium of its level; central differences of W_N(g_{n+1}), 1e-7 relative
// (the differences' own error at fd_step). With touchdown in the step too (g_n > 0), which "dd" averages.
TEST(PenaltyElement, StaticStepsForceIsThePenaltyEnergysGradientAtTheEnd) {
  for (const auto& [g_n, g_1] : {std::pair{-0.02, -0.03}, std::pair{0.01, -0.02}}) {
    const Step s = random_step(6, g_n, g_1);
    const PenaltyParameters p = parameters(NormalRule::discrete_derivative, 0.0, true);
    const auto at = [&](const Vector15& x) { return penalty_element(s.x_n, x, {}, p, s.xi_start); };
    Vector15 gradient;
    for (int j = 0; j < 15; ++j) {
      Vector15 up = s.x_1, down = s.x_1;
      up[j] += fd_step, down[j] -= fd_step;
      gradient[j] = (at(up).normal_energy - at(down).normal_energy) / (2 * fd_step);
    }
    const PenaltyResult r = at(s.x_1);
    ASSERT_TRUE(r.closed);
    EXPECT_LT((r.force - gradient).norm(), 1e-7 * gradient.norm()) << "g_n " << g_n;
    EXPECT_EQ(r.normal_traction, stiffness * r.at_1.gap) << "t_N = ε_N g_{n+1}";
  }
}

// ------------------------------------------------------------------------------------------------
// μ = 0 or ε_T = 0: frictionless, no NaN.
TEST(PenaltyElement, FrictionlessGivesNoTangentialTraction) {
  const Step s = random_step(5, -0.02, -0.03);
  for (const PenaltyParameters p :
       {PenaltyParameters{stiffness, stiffness, 0.0}, PenaltyParameters{stiffness, 0.0, 0.3}}) {
    const PenaltyResult r = penalty_element(s.x_n, s.x_1, s.history, p, s.xi_start);
    ASSERT_TRUE(r.closed);
    EXPECT_EQ(r.traction, Eigen::Vector2d::Zero());
    EXPECT_EQ(r.slip_work, 0.0);
    EXPECT_EQ(r.tangential_energy, 0.0);
    EXPECT_TRUE(r.force.allFinite() && r.tangent.allFinite());
    EXPECT_LT(relative_error(r.force, r.normal_traction * gap_gradient(r.at_m.frame)), 1e-15);
  }
}

TEST(PenaltyElement, DefaultStiffnessIsTenTimesYoungsModulusTimesFaceSize) {
  EXPECT_EQ(penalty_default_stiffness(1e4, 0.5), 5e4);  // §5.1
}

// ------------------------------------------------------------------------------------------------
// One fixed state against the design prototype (an independent Python implementation of §5.2, not
// shipped; its penalty element with commit=True; eps_n = eps_t = 1e3, c.xi = 0, c.tT = (0.8, -0.5, 0.1)),
// printed with repr() by:
//   Y = [[0,0,0],[1,0,0.1],[1.1,1,-0.05],[0,0.9,0.2]]; en = [0.55, 0.42, lift] + Y.ravel()
//   e1 = en + [0.02,-0.015,-0.012, 0.003,-0.002,0.001, -0.004,0.002,0.003, 0.001,0.0,-0.002,
//   0.002,-0.003,0.001] f = Model(zeros((5,3)))._pen_local(c, en, e1, commit=True)  -> force, c.tT, c.WN,
//   c.WT, c.diss
// and ‖K‖_F of the prototype's central-difference tangent (_penalty, step 1e-7).
struct PrototypeCase {
  std::string name;
  NormalRule rule;
  double friction, lift;
  bool slip;
  Vector15 force;
  Eigen::Vector3d history;
  double normal_energy, tangential_energy, slip_work, tangent_norm;
};

std::vector<PrototypeCase> prototype_cases() {
  auto vec15 = [](std::initializer_list<double> v) {
    return Vector15(Eigen::Map<const Vector15>(v.begin()));
  };
  return {
      // g_n = -0.059474931304947125, g_1 = -0.07119936321531303
      {"dd_slip",
       NormalRule::discrete_derivative,
       0.3,
       0.0,
       true,
       vec15({12.55776963617545, -9.9191548282961, -66.17775220795188, -3.2723764058871776, 2.590687048098287,
              17.528629107270273, -3.9024132000219764, 3.055938364168599, 19.29001564634906,
              -2.928116251493483, 2.312305809754216, 15.403828618136837, -2.4548637787728156,
              1.960223606274999, 13.955278836195708}),
       {16.083024937163447, -11.164518683379143, -0.9458776492389941},
       2.5346746611330353,
       0.19210242654413653,
       0.11376371970924616,
       1193.7225396835156},
      {"dd_stick",
       NormalRule::discrete_derivative,
       5.0,
       0.0,
       false,
       vec15({17.2373144639528, -13.108526595105536, -66.45219499370863, -4.492655021757567,
              3.423762510141673, 17.66693249353598, -5.352766991449427, 4.038198979629934, 19.075047727906874,
              -4.019172284418279, 3.055789771046075, 15.461475470434898, -3.372720166327525,
              2.590775334287857, 14.248739301830886}),
       {20.845236362451985, -14.470351923056548, -1.225953652710357},
       2.5346746611330353,
       0.3227089630710953,
       0.0,
       1886.1565524249495},
      {"mid_slip",
       NormalRule::midpoint,
       0.3,
       0.0,
       true,
       vec15({12.550799716095842, -9.91364941464276, -66.14102166922555, -3.2705601437100356,
              2.58924914294477, 17.518900218500818, -3.900247249466281, 3.0542422312737005,
              19.279309137845974, -2.9264910635144066, 2.311022414122624, 15.395279054201602,
              -2.453501259405118, 1.9591356263016644, 13.947533258677169}),
       {16.074098399912156, -11.15832205728988, -0.9453526601835096},
       2.5346746611330353,
       0.19188924107818817,
       0.11391370388974402,
       1192.9697586111824},
      // g_n = 0.005423857832407859, g_1 = -0.0062740018427563425 (touchdown: the "dd" quotient)
      {"dd_touchdown",
       NormalRule::discrete_derivative,
       0.3,
       0.065,
       true,
       vec15({0.32577112215117743, -0.2692791966724691, -1.70494483693694, -0.08560686951543303,
              0.070762654039653, 0.4480691381613487, -0.09917490139100878, 0.08197268729808425,
              0.5188386045755878, -0.07567091163272183, 0.06254880455486064, 0.3960276035914892,
              -0.06531843961201383, 0.053995050779871226, 0.34200949060851454}),
       {0.41007128544991467, -0.29325685116659256, -0.02473763730885055},
       0.01968154956145499,
       0.00012738499530315733,
       0.012899194979983595,
       515.5742854501783},
  };
}

TEST(PenaltyElement, MatchesThePrototype) {
  SegmentNodes nodes;
  nodes << 0, 0, 0, 1, 0, 0.1, 1.1, 1, -0.05, 0, 0.9, 0.2;
  Vector15 dx;
  dx << 0.02, -0.015, -0.012, 0.003, -0.002, 0.001, -0.004, 0.002, 0.003, 0.001, 0.0, -0.002, 0.002, -0.003,
      0.001;
  FrictionHistory history;
  history.traction = Eigen::Vector3d(0.8, -0.5, 0.1);
  for (const PrototypeCase& c : prototype_cases()) {
    SCOPED_TRACE(c.name);
    const Vector15 x_n = element_vector(Eigen::Vector3d(0.55, 0.42, c.lift), nodes), x_1 = x_n + dx;
    const PenaltyParameters p{stiffness, stiffness, c.friction, c.rule};
    const PenaltyResult r = penalty_element(x_n, x_1, history, p, Eigen::Vector2d::Zero());
    ASSERT_TRUE(r.closed);
    EXPECT_EQ(r.slip, c.slip);
    EXPECT_LT(relative_error(r.force, c.force), 1e-10);
    EXPECT_LT(relative_error(r.history_after.traction, c.history), 1e-10);
    EXPECT_NEAR(r.normal_energy, c.normal_energy, 1e-10 * c.normal_energy);
    EXPECT_NEAR(r.tangential_energy, c.tangential_energy, 1e-10 * c.tangential_energy);
    EXPECT_NEAR(r.slip_work, c.slip_work, 1e-10 * c.slip_work);
    // The prototype's tangent is a difference quotient with step 1e-7 (accurate to ~1e-8).
    EXPECT_NEAR(r.tangent.norm(), c.tangent_norm, 1e-7 * c.tangent_norm);
  }
}

}  // namespace
}  // namespace stoss::contact
