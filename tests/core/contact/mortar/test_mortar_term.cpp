// The mortar contact term (docs/theory.md §4.7, (4.81)–(4.84)) shall assemble a tangent that matches central
// differences of its residual, for the midpoint and the end-point force rules, and activate the slave nodes
// whose weighted gap is negative. Scene: a 2 × 2 cube bottom pressed into a 3 × 3 plate, every node jittered.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "core/contact/mortar/mortar_term.hpp"
#include "core/mesh/generators.hpp"
#include "tests/core/contact/ranks_test_utils.hpp"

namespace stoss::contact {
namespace {

struct Fixture {
  mesh::Mesh mesh;
  Eigen::VectorXd x_n, v_n, z;
  int nx = 0;
  std::unique_ptr<MortarContactTerm> term;
  std::unique_ptr<time::StepContext> step;

  /// `shift`: the cube moved along x (1.15: its bottom's middle row of nodes 0.05 past the plate's edge).
  /// `impact`: persist freezes each activated node's nodal gap at x_n (4.83), exact closes it.
  explicit Fixture(const time::ForceRule& rule, unsigned seed = 3, double shift = 0,
                   model::ImpactMode impact = model::ImpactMode::exact) {
    mesh.add_body("plate", mesh::box({-1, -1, -0.4}, {1, 1, 0}, {3, 3, 1}));
    mesh.add_body("cube", mesh::box({-0.55 + shift, -0.45, 0.0}, {0.45 + shift, 0.5, 0.6}, {2, 2, 1}));
    model::ContactPair pair;
    pair.slave = "cube/bottom";
    pair.master = "plate/top";
    pair.impact = impact;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-0.01, 0.01);
    x_n = mesh.reference_positions();
    nx = static_cast<int>(x_n.size());
    for (int i = 0; i < nx; ++i) x_n[i] += jitter(rng);
    v_n = Eigen::VectorXd::Zero(nx);
    for (int I = mesh.bodies[1].node_begin; I < mesh.bodies[1].node_end; ++I) v_n[3 * I + 2] = -3;
    term = std::make_unique<MortarContactTerm>(mesh, pair, rule);
    step = std::make_unique<time::StepContext>(time::StepContext{x_n, v_n, 0.01, rule});
    term->prepare_step(*step);
    term->set_auxiliary_offset(nx);
    z = Eigen::VectorXd::Zero(nx + term->auxiliary_count());
    z.head(nx) = x_n + step->h * v_n;  // 0.03 below the plate's top
    for (int i = 0; i < nx; ++i) z[i] += 0.2 * jitter(rng);
    term->begin_step(*step, z);
    term->update_active_set(*step, z);
    std::normal_distribution<double> normal(-1, 0.3);
    for (int i = nx; i < z.size(); ++i) z[i] = normal(rng);  // every multiplier, the inactive rows' too
  }
  Eigen::VectorXd residual(const Eigen::VectorXd& at) const {
    Eigen::VectorXd R = Eigen::VectorXd::Zero(at.size());
    term->add(*step, at, R, nullptr);
    return R;
  }
  Eigen::MatrixXd tangent() const {
    solve::BlockPattern pattern;
    term->register_blocks(pattern);
    pattern.build(static_cast<int>(z.size()));
    pattern.zero();
    Eigen::VectorXd R = Eigen::VectorXd::Zero(z.size());
    term->add(*step, z, R, &pattern);
    return Eigen::MatrixXd(pattern.matrix());
  }
};

double relative_tangent_error(const Fixture& f) {
  const Eigen::MatrixXd K = f.tangent();
  Eigen::MatrixXd fd(K.rows(), K.cols());
  const double e = 1e-6;
  for (int c = 0; c < f.z.size(); ++c) {
    Eigen::VectorXd zp = f.z, zm = f.z;
    zp[c] += e, zm[c] -= e;
    fd.col(c) = (f.residual(zp) - f.residual(zm)) / (2 * e);
  }
  return (K - fd).norm() / K.norm();
}

TEST(MortarTerm, EveryPenetratingSlaveNodeIsActivated) {
  const Fixture f(time::ForceRule::midpoint());
  int active = 0;
  for (char a : f.term->active()) active += a;
  EXPECT_EQ(active, 9);  // the 3 × 3 nodes of the cube's bottom, all 0.03 ± 0.01 deep
  Eigen::VectorXd gap, weight;
  f.term->nodal_gaps(f.z.head(f.nx), gap, weight);
  EXPECT_NEAR(weight.sum(), 0.95, 0.02);  // Σ D_jj = the bottom's area (1.0 × 0.95, jittered)
  EXPECT_LT(gap.maxCoeff(), 0);
}

// Two ranks played in one process (ranks_test_utils.hpp): a face pair is computed by the owner of its slave
// face's first node, a multiplier row by its node's.
TEST(MortarTerm, OnTwoRanksEachComputesItsSlaveNodesAndEveryRankGetsOneProcesssRows) {
  for (const time::ForceRule& rule : {time::ForceRule::midpoint(), time::ForceRule::end_point(0.9, 0.1)}) {
    Fixture f(rule);
    if (rule.previous_weight != 0) {  // λ_n ∂g̃/∂x(x_n) of the last step too (4.82)
      f.term->end_step(*f.step, f.z);
      f.term->prepare_step(*f.step);
      f.term->set_auxiliary_offset(f.nx);
      f.term->begin_step(*f.step, f.z);
    }
    test::expect_one_process_rows(test::play_two_ranks(*f.term, f.mesh, *f.step, f.z));
  }
}

TEST(MortarTerm, MidpointTangentMatchesCentralDifferences) {
  const double error = relative_tangent_error(Fixture(time::ForceRule::midpoint()));
  std::printf("mortar midpoint: |K − K_fd| / |K| = %.2e\n", error);
  EXPECT_LT(error, 1e-6);
}

// The energy–momentum rule's force is the discrete gradient of §4.7.2: its tangent (4.88) in the term's
// blocks.
TEST(MortarTerm, DiscreteGradientTangentMatchesCentralDifferences) {
  const double error = relative_tangent_error(Fixture(time::ForceRule::discrete_gradient()));
  std::printf("mortar discrete gradient: |K − K_fd| / |K| = %.2e\n", error);
  EXPECT_LT(error, 1e-6);
}

// With persist each activated node carries its frozen nodal gap ḡ⁰_j inside the integral, g̃_j = ∫ Φ_j (g −
// ḡ⁰_j) (4.83): the tangent includes ḡ⁰_j's share, −ḡ⁰_j ∂(∫ Φ_j)/∂x.
TEST(MortarTerm, PersistTangentMatchesCentralDifferences) {
  for (const time::ForceRule& rule : {time::ForceRule::midpoint(), time::ForceRule::discrete_gradient()}) {
    const Fixture f(rule, 3, 0, model::ImpactMode::persist);
    Eigen::VectorXd gap, weight;
    f.term->nodal_gaps(f.x_n, gap, weight);
    const double error = relative_tangent_error(f);
    std::printf("mortar persist: |K − K_fd| / |K| = %.2e, largest |g̃_j(x_n; ḡ⁰_j)| = %.1e\n", error,
                gap.cwiseAbs().maxCoeff());
    EXPECT_LT(error, 1e-6);
  }
}

// (4.84): only nodes whose D_jj covers half of their coverable support activate. The cube moved to overhang
// the plate's edge (x = 1): its bottom's first row of nodes (x = 0.6) lies over the plate; the middle row (x
// = 1.1) has 80 % of its inner faces over the plate, where the dual basis gives it D_jj = 0.34 of their ∫ N_j
// and a negative weighted gap (the rule before, D_jj > 0, activated it); the last row (x = 1.6) overlaps
// nothing.
TEST(MortarTerm, OnlySlaveNodesTheMasterCoversActivate) {
  const Fixture f(time::ForceRule::midpoint(), 3, 1.15);
  Eigen::VectorXd gap, weight, support;
  f.term->nodal_gaps(f.z.head(f.nx), gap, weight, &support);
  int active = 0;
  for (size_t j = 0; j < f.term->active().size(); ++j) {
    const double x = f.mesh.reference_positions()[3 * f.term->surfaces().slave_nodes[j]];
    std::printf("slave node at x = %.2f: D_jj %.4f, support %.4f, g̃_j %.2e, active %d\n", x, weight[j],
                support[j], gap[j], f.term->active()[j]);
    EXPECT_EQ(f.term->active()[j] != 0, x < 1)
        << "x = " << x << ", D_jj / support = " << weight[j] / support[j];
    active += f.term->active()[j];
  }
  EXPECT_EQ(active, 3);
}

TEST(MortarTerm, EndPointTangentMatchesCentralDifferences) {
  const double error = relative_tangent_error(Fixture(time::ForceRule::end_point(2.0 / 3, 1.0 / 3)));
  std::printf("mortar end point: |K − K_fd| / |K| = %.2e\n", error);
  EXPECT_LT(error, 1e-6);
}

// The kernel's gradient at a slave edge tilted by e against a collinear master edge (what the patch test's
// rim gives a Newton iterate), the slave corner on the master's edge. Before each clip vertex was kept the
// intersection of its own edges' lines (4.70), the dual numbers gave −0.89 at e = 1e-5 and −8.9e3 at e = 1e-9
// (∝ 1/e), against 1.2098765e-5. Reference: forward differences, h = 1e-7: moving the corner up keeps the
// topology (the master's edge bounds the overlap). Central differences with h = 1e-4 e, as this test first
// used, are round-off at e = 1e-9 (g̃ carries ~5e-18 of it, from x_s − y with coordinates ~0.5: 2.4e-6 off).
// At e = 0 the overlap has a kink there; the kernel must give one of the two one-sided derivatives.
TEST(MortarTerm, GradientStaysBoundedAtNearlyParallelEdges) {
  SegmentNodes master;
  master << 1.0 / 3, 2.0 / 3, 0.5, 2.0 / 3, 2.0 / 3, 0.5, 2.0 / 3, 1, 0.5, 1.0 / 3, 1, 0.5;
  const auto gap = [&](const SegmentNodes& slave) {
    return mortar::pair_gaps(slave, master, mortar::Multipliers::dual).gap[2];
  };
  for (double e : {1e-5, 1e-7, 1e-9, 1e-12, 0.0}) {
    SegmentNodes slave;
    slave << 0, 0.5, 0.5 - 4e-5, 0, 1 + e, 0.5 - 4e-5, 0.5, 1, 0.5 - 4e-5, 0.5, 0.5, 0.5 - 4e-5;
    const mortar::PairGaps g = mortar::pair_gaps(slave, master, mortar::Multipliers::dual);
    const double h = 1e-7;
    SegmentNodes up = slave, down = slave;
    up(2, 1) += h, down(2, 1) -= h;
    const double forward = (gap(up) - g.gap[2]) / h, backward = (g.gap[2] - gap(down)) / h;
    std::printf("e = %.0e: ∂g̃₂/∂y = %.10e, forward %.10e, backward %.10e\n", e, g.gradient(2, 7), forward,
                backward);
    if (e > 0)
      EXPECT_NEAR(g.gradient(2, 7), forward, 1e-9) << "e = " << e;
    else
      EXPECT_LT(std::min(std::abs(g.gradient(2, 7) - forward), std::abs(g.gradient(2, 7) - backward)), 1e-9);
  }
}

// A Newton iterate that folds a slave face (its projection no longer convex, (4.70)) is no configuration to
// integrate on: the term gives a residual that is not finite, so that Newton backtracks or the step shrinks,
// instead of throwing out of the run. Here one corner of a cube face is pulled inside the triangle of the
// other three.
TEST(MortarTerm, AFoldedSlaveFaceGivesANonFiniteResidualNotAnException) {
  const Fixture f(time::ForceRule::midpoint());
  ASSERT_TRUE(f.tangent().allFinite());  // registers the pairs' dofs, as a run's first assembly does
  ASSERT_TRUE(f.residual(f.z).allFinite());
  const mesh::Quad q = f.mesh.surface("cube/bottom").front();
  Eigen::VectorXd folded = f.z;
  folded.segment<3>(3 * q[2]) =
      f.z.segment<3>(3 * q[0]) + 0.2 * (f.z.segment<3>(3 * q[2]) - f.z.segment<3>(3 * q[0]));
  Eigen::VectorXd R;
  ASSERT_NO_THROW(R = f.residual(folded));
  EXPECT_FALSE(R.allFinite());
}

// Checkpoint and resume: a term given the saved state of a converged step (active set, λ_n, frozen gaps)
// shall assemble the next step exactly as the term that took it. The end-point rule with w_n ≠ 0 uses λ_n.
TEST(MortarTerm, ARestoredStateAssemblesTheNextStepAsTheOriginal) {
  const time::ForceRule rule = time::ForceRule::end_point(0.9, 0.1);
  Fixture original(rule), resumed(rule);
  original.term->end_step(*original.step, original.z);
  const time::TermState state = original.term->save_state();
  const Eigen::VectorXd x_1 = original.z.head(original.nx), v_1 = Eigen::VectorXd::Zero(original.nx);
  resumed.term->restore_state(state, x_1, v_1);
  const time::StepContext next{x_1, v_1, 0.01, rule};
  Eigen::VectorXd R_original = Eigen::VectorXd::Zero(original.z.size()), R_resumed = R_original;
  solve::BlockPattern patterns[2];
  original.term->prepare_step(next);
  resumed.term->prepare_step(next);
  original.term->register_blocks(patterns[0]);  // as the integrator does on a new structure generation
  resumed.term->register_blocks(patterns[1]);
  original.term->add(next, original.z, R_original, nullptr);
  resumed.term->add(next, original.z, R_resumed, nullptr);
  EXPECT_EQ(original.term->active(), resumed.term->active());
  EXPECT_GT(std::count(resumed.term->active().begin(), resumed.term->active().end(), 1), 0);
  EXPECT_EQ((R_original - R_resumed).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_GT(R_original.head(original.nx).cwiseAbs().maxCoeff(), 0.0) << "λ_n's force is in the rows";
}

}  // namespace
}  // namespace stoss::contact
