// The penalty contact term shall assemble h·(5.2) with a tangent that matches central differences of
// its residual in stick and in slip (docs/theory.md §6.1), commit the friction history only in
// end_step and reset it when a contact opens (§5.2 item 7), and never run the return mapping of a
// frictionless pair (§5.1, μ = 0). Scene: one hex8 cube pressed into a 2 × 2 plate, sliding along x.
#include <gtest/gtest.h>

#include <random>

#include "core/contact/contact.hpp"
#include "core/contact/penalty/penalty_term.hpp"
#include "core/mesh/generators.hpp"
#include "tests/core/contact/ranks_test_utils.hpp"

namespace stoss::contact {
namespace {

constexpr double youngs_modulus = 300;
constexpr double stiffness = 1e3;  // ε_N = ε_T: gaps ~0.03 give t_N ~ 30, Δx = 0.02 gives ‖t^tr‖ ~ 20

mesh::Mesh cube_in_plate() {
  mesh::Mesh m;
  m.add_body("plate", mesh::box({-1, -1, -0.4}, {1, 1, 0}, {2, 2, 1}));
  m.add_body("cube", mesh::box({-0.35, -0.3, -0.02}, {0.25, 0.3, 0.58}, {1, 1, 1}));
  return m;
}

model::ContactPair penalty_pair(double friction, bool default_stiffness = false) {
  model::ContactPair p;
  p.slave = "cube/bottom";
  p.master = "plate/top";
  p.enforcement = model::Enforcement::penalty;
  p.friction = friction;
  if (!default_stiffness) p.normal_stiffness = p.tangential_stiffness = stiffness;
  return p;
}

/// Two steps of the cube sliding (v_x = 2) and sinking (v_z = −1) into a jittered plate: the first one
/// committed (it leaves a friction history), the second one to check.
struct Fixture {
  mesh::Mesh mesh = cube_in_plate();
  PenaltyContactTerm term;
  Eigen::VectorXd x_n, v_n, x_1;
  double h = 0.01;
  std::unique_ptr<time::StepContext> step;

  Fixture(double friction, unsigned seed) : term(mesh, penalty_pair(friction), youngs_modulus) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-0.005, 0.005);
    Eigen::VectorXd x_0 = mesh.reference_positions();
    for (int i = 0; i < x_0.size(); ++i) x_0[i] += jitter(rng);
    v_n = Eigen::VectorXd::Zero(x_0.size());
    for (int I = mesh.bodies[1].node_begin; I < mesh.bodies[1].node_end; ++I) {
      v_n[3 * I] = 2;
      v_n[3 * I + 2] = -1;
    }
    x_n = x_0 + h * v_n;
    const time::StepContext first{x_0, v_n, h, time::ForceRule::discrete_gradient()};
    term.prepare_step(first);
    term.end_step(first, x_n);  // commits t_{T,n} ≠ 0 (stick or slip)
    x_1 = x_n + h * v_n;
    for (int i = 0; i < x_1.size(); ++i) x_1[i] += 0.2 * jitter(rng);
    step = std::make_unique<time::StepContext>(
        time::StepContext{x_n, v_n, h, time::ForceRule::discrete_gradient()});
    term.prepare_step(*step);
  }

  Eigen::VectorXd residual(const Eigen::VectorXd& at) const {
    Eigen::VectorXd R = Eigen::VectorXd::Zero(at.size());
    term.add(*step, at, R, nullptr);
    return R;
  }
  Eigen::MatrixXd jacobian() {
    solve::BlockPattern P;
    term.register_blocks(P);
    P.build(static_cast<int>(x_1.size()));
    Eigen::VectorXd R = Eigen::VectorXd::Zero(x_1.size());
    term.add(*step, x_1, R, &P);
    return Eigen::MatrixXd(P.matrix());
  }
  Eigen::MatrixXd fd_jacobian(double eps) const {
    Eigen::MatrixXd J(x_1.size(), x_1.size());
    for (int j = 0; j < x_1.size(); ++j) {
      Eigen::VectorXd plus = x_1, minus = x_1;
      plus[j] += eps;
      minus[j] -= eps;
      J.col(j) = (residual(plus) - residual(minus)) / (2 * eps);
    }
    return J;
  }
  /// Elements of the step that close, and how many of them slip, at x_1.
  std::pair<int, int> closed_and_slipping() const {
    int closed = 0, slipping = 0;
    for (const PenaltyContact& c : term.contacts()) {
      const int node = term.surfaces().slave_nodes[c.slave];
      const mesh::Quad& face = term.surfaces().faces[c.face];
      const PenaltyResult r =
          penalty_element(element_positions(node, face, x_n), element_positions(node, face, x_1), c.history,
                          term.parameters(), c.xi_n);
      closed += r.closed;
      slipping += r.slip;
    }
    return {closed, slipping};
  }
};

struct Regime {
  const char* name;
  double friction;
  bool slip;
};

class PenaltyTermTangent : public ::testing::TestWithParam<std::tuple<Regime, unsigned>> {};

TEST_P(PenaltyTermTangent, MatchesCentralDifferencesOfTheResidual) {
  const auto& [regime, seed] = GetParam();
  Fixture f(regime.friction, seed);
  const auto [closed, slipping] = f.closed_and_slipping();
  ASSERT_EQ(closed, 4) << "all four bottom nodes of the cube are pressed into the plate";
  EXPECT_EQ(slipping, regime.slip ? 4 : 0) << regime.name;
  const Eigen::MatrixXd K = f.jacobian(), K_fd = f.fd_jacobian(1e-7);
  ASSERT_GT(K_fd.norm(), 0);
  EXPECT_LT((K - K_fd).norm() / K_fd.norm(), 1e-6) << regime.name << ", seed " << seed;
  EXPECT_GT((K - K.transpose()).norm(), 1e-3 * K.norm()) << "the friction tangent is not symmetric";
}

INSTANTIATE_TEST_SUITE_P(StickAndSlip, PenaltyTermTangent,
                         ::testing::Combine(::testing::Values(Regime{"stick", 5.0, false},
                                                              Regime{"slip", 0.1, true}),
                                            ::testing::Values(1u, 2u, 3u)),
                         [](const auto& info) {
                           return std::string(std::get<0>(info.param).name) + "_" +
                                  std::to_string(std::get<1>(info.param));
                         });

// Two ranks played in one process (ranks_test_utils.hpp), with friction, two nodes sticking or slipping each.
TEST(PenaltyTerm, OnTwoRanksEachComputesItsSlaveNodesAndEveryRankGetsOneProcesssRows) {
  Fixture f(0.3, 2);
  ASSERT_EQ(f.closed_and_slipping().first, 4) << "every bottom node closed";
  test::expect_one_process_rows(test::play_two_ranks(f.term, f.mesh, *f.step, f.x_1));
}

TEST(PenaltyTerm, CommitsTheHistoryOnlyInEndStepAndResetsItWhenTheContactOpens) {
  Fixture f(0.1, 4);
  const std::vector<PenaltyNodeState> before = f.term.node_states();
  int with_history = 0;
  for (const PenaltyNodeState& s : before) with_history += s.history.traction.norm() > 0;
  EXPECT_EQ(with_history, 4) << "the first (committed) step left a traction at each bottom node";
  f.residual(f.x_1);
  f.jacobian();
  for (size_t i = 0; i < before.size(); ++i)
    EXPECT_EQ(f.term.node_states()[i].history.traction, before[i].history.traction) << "Newton never commits";
  Eigen::VectorXd lifted = f.x_n;
  for (int I = f.mesh.bodies[1].node_begin; I < f.mesh.bodies[1].node_end; ++I) lifted[3 * I + 2] += 0.1;
  f.term.end_step(*f.step, lifted);  // every contact opens: g_n < 0 < g_{n+1} with "dd" is closed ...
  const time::StepContext next{lifted, f.v_n, f.h, time::ForceRule::discrete_gradient()};
  f.term.prepare_step(next);
  f.term.end_step(next, lifted);  // ... so one more step with g_n, g_{n+1} > 0 opens them
  for (const PenaltyNodeState& s : f.term.node_states()) EXPECT_EQ(s.history.traction.norm(), 0.0);
  EXPECT_EQ(f.term.report().active, 0);
}

TEST(PenaltyTerm, SlipDissipatesStickDoesNot) {
  Fixture slipping(0.1, 5), sticking(5.0, 5);
  slipping.term.end_step(*slipping.step, slipping.x_1);
  sticking.term.end_step(*sticking.step, sticking.x_1);
  EXPECT_GT(slipping.term.last_slip_work(), 0);
  EXPECT_EQ(sticking.term.last_slip_work(), 0.0) << "exactly 0 in stick (§5.2 item 7)";
  EXPECT_EQ(sticking.term.dissipated_energy(), 0.0);
}

TEST(PenaltyTerm, AFrictionlessPairNeverRunsTheReturnMapping) {
  Fixture frictionless(0.0, 6), frictional(0.3, 6);
  frictionless.jacobian();
  frictionless.term.end_step(*frictionless.step, frictionless.x_1);
  frictional.jacobian();
  EXPECT_EQ(frictionless.closed_and_slipping().first, 4) << "the contacts are closed";
  EXPECT_EQ(frictionless.term.return_map_evaluations(), 0);
  EXPECT_EQ(frictionless.term.parameters().tangential_stiffness, 0.0);
  EXPECT_EQ(frictionless.term.dissipated_energy(), 0.0);
  EXPECT_GT(frictional.term.return_map_evaluations(), 0);
}

TEST(PenaltyTerm, DefaultStiffnessIsTenTimesYoungsModulusTimesTheMeanMasterFaceSize) {
  const mesh::Mesh m = cube_in_plate();
  const PenaltyContactTerm term(m, penalty_pair(0.2, true), youngs_modulus);
  EXPECT_DOUBLE_EQ(term.parameters().normal_stiffness, 10 * youngs_modulus * 1.0);  // ℓ = 1 (§5.1)
  EXPECT_DOUBLE_EQ(term.parameters().tangential_stiffness, 10 * youngs_modulus * 1.0);
}

TEST(PenaltyTerm, EnergyIsThePenaltyEnergyOfThePenetratingNodes) {
  const mesh::Mesh m = cube_in_plate();
  const PenaltyContactTerm term(m, penalty_pair(0.2), youngs_modulus);
  const Eigen::VectorXd x = m.reference_positions();                      // bottom nodes 0.02 below the plate
  EXPECT_NEAR(term.energy(x), 4 * 0.5 * stiffness * 0.02 * 0.02, 1e-12);  // 4 W_N (5.1)
}

TEST(PenaltyTerm, HhtIsRejectedByName) {
  model::Model m;
  m.mesh = cube_in_plate();
  for (const char* name : {"plate", "cube"}) {
    model::BodySpec body;
    body.name = name;
    body.material = {"saint_venant_kirchhoff", youngs_modulus, 0.3, 1};
    m.bodies.push_back(body);
  }
  m.contact = {penalty_pair(0.2)};
  m.time.scheme = model::Scheme::hht;
  try {
    make_pair_term(m, m.contact[0]);
    FAIL() << "penalty contact with hht is not implemented";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(
        std::string(e.what()),
        "contact pair cube/bottom / plate/top: enforcement \"penalty\" is not implemented with time.scheme "
        "\"hht\"; use energy_momentum or midpoint");
  }
  m.time.scheme = model::Scheme::midpoint;
  EXPECT_NE(dynamic_cast<PenaltyContactTerm*>(make_pair_term(m, m.contact[0]).get()), nullptr);
}

}  // namespace
}  // namespace stoss::contact
