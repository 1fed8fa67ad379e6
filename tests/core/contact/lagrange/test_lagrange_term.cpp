// The contact terms shall assemble tangents that match central differences of their residuals
// (docs/theory.md §6.1: (4.2) with (3.9), (4.9)–(4.10)), and run the active set (§3.5) and the face
// switch (§3.4) as specified. Scene: one hex8 cube over a 2 × 2 plate, its bottom nodes on different faces.
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <set>
#include <stdexcept>

#include "core/contact/contact.hpp"
#include "core/contact/lagrange/elements/mixed_term.hpp"
#include "core/contact/lagrange/elements/nts_term.hpp"
#include "core/mesh/generators.hpp"
#include "core/time/scheme.hpp"
#include "tests/core/contact/ranks_test_utils.hpp"

namespace stoss::contact {
namespace {

mesh::Mesh cube_over_plate() {
  mesh::Mesh m;
  m.add_body("plate", mesh::box({-1, -1, -0.4}, {1, 1, 0}, {2, 2, 1}));
  m.add_body("cube", mesh::box({-0.35, -0.3, 0.02}, {0.25, 0.3, 0.62}, {1, 1, 1}));
  return m;
}

model::ContactPair pair(model::ImpactMode impact = model::ImpactMode::exact) {
  model::ContactPair p;
  p.slave = "cube/bottom";
  p.master = "plate/top";
  p.impact = impact;
  return p;
}

/// The Lagrange term the module's factory builds for `p` in a run of `scheme` on `mesh`.
std::unique_ptr<LagrangeContactTerm> lagrange_term(const mesh::Mesh& mesh, const model::ContactPair& p,
                                                   model::Scheme scheme) {
  model::Model m;
  m.mesh = mesh;
  m.time.scheme = scheme;
  std::unique_ptr<ContactTerm> term = make_pair_term(m, p);
  if (!dynamic_cast<LagrangeContactTerm*>(term.get())) throw std::logic_error("not a Lagrange contact term");
  return std::unique_ptr<LagrangeContactTerm>(static_cast<LagrangeContactTerm*>(term.release()));
}

/// A step of the cube falling onto the plate with every node jittered, and its contact elements.
struct Fixture {
  mesh::Mesh mesh = cube_over_plate();
  Eigen::VectorXd x_n, v_n, z;
  double h = 0.01;
  int nx = 0;
  std::unique_ptr<LagrangeContactTerm> term;
  std::unique_ptr<time::StepContext> step;

  Fixture(model::Scheme scheme, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-0.01, 0.01);
    x_n = mesh.reference_positions();
    nx = static_cast<int>(x_n.size());
    for (int i = 0; i < nx; ++i) x_n[i] += jitter(rng);
    v_n = Eigen::VectorXd::Zero(nx);
    for (int I = mesh.bodies[1].node_begin; I < mesh.bodies[1].node_end; ++I)
      v_n[3 * I + 2] = -5;  // −0.05 per step
    term = lagrange_term(mesh, pair(), scheme);
    const time::ForceRule rule = time::make_scheme(model::TimeSpec{scheme})->force_rule();
    step = std::make_unique<time::StepContext>(time::StepContext{x_n, v_n, h, rule});
    term->prepare_step(*step);
    term->set_auxiliary_offset(nx);
    Eigen::VectorXd x_1 = x_n + h * v_n;
    for (int i = 0; i < nx; ++i) x_1[i] += 0.2 * jitter(rng);
    term->update_active_set(*step, x_1);  // every bottom node is below the plate now
    term->set_auxiliary_offset(nx);
    z = Eigen::VectorXd::Zero(nx + term->auxiliary_count());
    z.head(nx) = x_1;
    term->initialize_auxiliaries(*step, z);
    std::normal_distribution<double> normal(0, 1);
    for (int i = nx; i < z.size(); ++i) z[i] += 0.05 * normal(rng);  // d, ξ off the CPP; λ random
  }

  Eigen::VectorXd residual(const Eigen::VectorXd& at) const {
    Eigen::VectorXd R = Eigen::VectorXd::Zero(at.size());
    term->add(*step, at, R, nullptr);
    return R;
  }
  Eigen::MatrixXd jacobian() const {
    solve::BlockPattern P;
    term->register_blocks(P);
    P.build(static_cast<int>(z.size()));
    Eigen::VectorXd R = Eigen::VectorXd::Zero(z.size());
    term->add(*step, z, R, &P);
    return Eigen::MatrixXd(P.matrix());
  }
  Eigen::MatrixXd fd_jacobian(double eps) const {
    Eigen::MatrixXd J(z.size(), z.size());
    for (Eigen::Index j = 0; j < z.size(); ++j) {
      Eigen::VectorXd zp = z, zm = z;
      zp[j] += eps;
      zm[j] -= eps;
      J.col(j) = (residual(zp) - residual(zm)) / (2 * eps);
    }
    return J;
  }
};

using Case = std::tuple<model::Scheme, unsigned>;
class ContactTermTangent : public ::testing::TestWithParam<Case> {};

TEST_P(ContactTermTangent, MatchesCentralDifferencesOfTheAssembledResidual) {
  const auto [scheme, seed] = GetParam();
  const Fixture f(scheme, seed);
  ASSERT_EQ(f.term->elements().size(), 4u) << "all four bottom nodes active";
  std::set<int> faces;
  for (const ContactElement& e : f.term->elements()) faces.insert(e.face);
  EXPECT_GE(faces.size(), 2u) << "the slave nodes lie on different master faces";
  const Eigen::MatrixXd K = f.jacobian(), K_fd = f.fd_jacobian(1e-6);
  EXPECT_GT(K_fd.norm(), 0);
  EXPECT_LT((K - K_fd).norm() / K_fd.norm(), 1e-6);  // §6.1
}

INSTANTIATE_TEST_SUITE_P(Schemes, ContactTermTangent,
                         ::testing::Combine(::testing::Values(model::Scheme::energy_momentum,
                                                              model::Scheme::midpoint),
                                            ::testing::Values(1u, 2u, 3u)),
                         [](const auto& info) {
                           return std::string(std::get<0>(info.param) == model::Scheme::midpoint ? "midpoint"
                                                                                                 : "mixed") +
                                  std::to_string(std::get<1>(info.param));
                         });

TEST(ContactTerm, LayoutIsElevenUnknownsPerMixedElementAndOnePerMidpointElement) {
  const Fixture mixed(model::Scheme::energy_momentum, 1), mid(model::Scheme::midpoint, 1);
  EXPECT_EQ(mixed.term->auxiliary_count(), 44);
  EXPECT_EQ(mid.term->auxiliary_count(), 4);
}

TEST(ContactTerm, ReleasesTensileMultipliersOnceAndKeepsASecondToggle) {
  Fixture f(model::Scheme::energy_momentum, 4);
  const int generation = f.term->structure_generation();
  Eigen::VectorXd z = f.z;
  z[f.nx + 5] = 1.0;  // λ_1 of the first element turns tensile; it was activated in this very step
  EXPECT_FALSE(f.term->update_active_set(*f.step, z)) << "activated and released in one step: kept (§3.5)";
  EXPECT_EQ(f.term->elements().size(), 4u);
  EXPECT_EQ(f.term->structure_generation(), generation);
  f.term->end_step(*f.step, z);
  // Next step: the element is old now, a tensile λ_1 releases it and the set shrinks.
  const Eigen::VectorXd x_1 = z.head(f.nx), v_1 = Eigen::VectorXd::Zero(f.nx);
  const time::StepContext next{x_1, v_1, f.h, time::ForceRule::discrete_gradient()};
  f.term->prepare_step(next);
  f.term->set_auxiliary_offset(f.nx);
  Eigen::VectorXd z2 = Eigen::VectorXd::Zero(f.nx + f.term->auxiliary_count());
  z2.head(f.nx) = x_1;
  f.term->initialize_auxiliaries(next, z2);
  z2[f.nx + 5] = 1.0;
  for (int k = 1; k < 4; ++k) z2[f.nx + 11 * k + 5] = -1.0;
  EXPECT_TRUE(f.term->update_active_set(next, z2));
  EXPECT_EQ(f.term->elements().size(), 3u);
  EXPECT_EQ(f.term->report().releases, 1);
}

TEST(ContactTerm, ActivationFreezesTheStartGapInPersistMode) {
  // R1 (§4.5): f_3 = g_N(x_n) ≥ 0 of the activation step; (4.11) then gives g(π_n) = 0.
  const mesh::Mesh m = cube_over_plate();
  MixedContactTerm term(m, pair(model::ImpactMode::persist));
  const Eigen::VectorXd x_n = m.reference_positions();
  Eigen::VectorXd v_n = Eigen::VectorXd::Zero(x_n.size());
  for (int I = m.bodies[1].node_begin; I < m.bodies[1].node_end; ++I) v_n[3 * I + 2] = -3;
  const time::StepContext step{x_n, v_n, 0.01, time::ForceRule::discrete_gradient()};
  term.prepare_step(step);
  term.set_auxiliary_offset(static_cast<int>(x_n.size()));
  ASSERT_TRUE(term.update_active_set(step, x_n + 0.01 * v_n));
  for (const ContactElement& e : term.elements()) {
    EXPECT_NEAR(e.f3, 0.02, 1e-14);
    EXPECT_LT(e.g_n.cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_TRUE(e.jump);
  }
}

TEST(ContactTerm, SwitchesFaceOnlyBeyondTheHysteresisWithTheClampedGapTarget) {
  // A node that slid from face A beyond ξ¹ = 1 + ε_sw moves to the neighbour at the next step start,
  // re-projected there, with f_3 = min(max(g_new, 0), f_3^old) (§3.4).
  const mesh::Mesh m = cube_over_plate();
  MixedContactTerm term(m, pair(model::ImpactMode::persist));
  Eigen::VectorXd x = m.reference_positions();
  Eigen::VectorXd v = Eigen::VectorXd::Zero(x.size());
  for (int I = m.bodies[1].node_begin; I < m.bodies[1].node_end; ++I) v[3 * I + 2] = -3;
  const time::StepContext first{x, v, 0.01, time::ForceRule::discrete_gradient()};
  term.prepare_step(first);
  term.set_auxiliary_offset(static_cast<int>(x.size()));
  term.update_active_set(first, x + 0.01 * v);
  term.set_auxiliary_offset(static_cast<int>(x.size()));
  Eigen::VectorXd z = Eigen::VectorXd::Zero(x.size() + term.auxiliary_count());
  z.head(x.size()) = x + 0.01 * v;
  term.initialize_auxiliaries(first, z);
  // The step ends with the first element's node slid across x = 0 onto the neighbouring face:
  // ξ¹ = ±1.2 on its own face, beyond 1 + ε_sw.
  const ContactElement before = term.elements()[0];
  const int node = term.surfaces().slave_nodes[before.slave];
  Eigen::Vector3d moved = z.segment<3>(3 * node);
  moved.x() = moved.x() < 0 ? 0.1 : -0.1;
  z.segment<3>(3 * node) = moved;
  const FaceProjection old_face =
      project_on(moved, before.face, term.surfaces(), z.head(x.size()), before.xi);
  ASSERT_NEAR(std::abs(old_face.projection.xi[0]), 1.2, 1e-12);
  z.segment<2>(x.size() + 3) = old_face.projection.xi;
  term.end_step(first, z);
  const int generation = term.structure_generation();
  const Eigen::VectorXd x1 = z.head(x.size()), v1 = Eigen::VectorXd::Zero(x.size());
  const time::StepContext second{x1, v1, 0.01, time::ForceRule::discrete_gradient()};
  term.prepare_step(second);
  const ContactElement& after = term.elements()[0];
  EXPECT_NE(after.face, before.face);
  EXPECT_GT(term.structure_generation(), generation);
  EXPECT_EQ(term.report().switches, 1);
  EXPECT_TRUE(after.jump);
  EXPECT_LE(after.xi_n.cwiseAbs().maxCoeff(), 1 + 1e-6);
  EXPECT_NEAR(after.f3, std::min(std::max(moved.z(), 0.0), before.f3), 1e-12);
}

TEST(ContactTerm, UnsupportedCombinationsAreRejectedByName) {
  const mesh::Mesh m = cube_over_plate();
  model::ContactPair p = pair();
  EXPECT_NE(dynamic_cast<NtsContactTerm*>(lagrange_term(m, p, model::Scheme::hht).get()), nullptr);
  p.impact = model::ImpactMode::velocity_correction;
  EXPECT_THROW(lagrange_term(m, p, model::Scheme::midpoint), std::invalid_argument);
  EXPECT_THROW(lagrange_term(m, p, model::Scheme::hht), std::invalid_argument);
  p = pair();
  p.friction = 0.3;
  try {
    lagrange_term(m, p, model::Scheme::energy_momentum);
    FAIL() << "frictional Lagrange contact is not implemented";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "contact pair cube/bottom / plate/top: enforcement \"lagrange\" is frictionless; friction > 0 "
              "needs enforcement \"penalty\"");
  }
}

// A resumed run's end-point term must add the t_n force (2.11) of the step it resumes after, as the
// term that ran that step does: restore_state rebuilds it although the replayed end_step has no rule.
TEST(ContactTerm, RestoredEndPointTermAddsTheSameTnForce) {
  Fixture f(model::Scheme::hht, 7);
  for (int i = f.nx; i < f.z.size(); ++i) f.z[i] = 1.0 + 0.1 * (i - f.nx);  // λ_n > 0: a t_n force
  f.term->end_step(*f.step, f.z);
  const Eigen::VectorXd x_1 = f.z.head(f.nx), v_1 = f.v_n;
  std::unique_ptr<LagrangeContactTerm> restored = lagrange_term(f.mesh, pair(), model::Scheme::hht);
  restored->restore_state(f.term->save_state(), x_1, v_1);
  const time::StepContext next{x_1, v_1, f.h, f.step->rule};
  Eigen::VectorXd R_ran, R_restored;
  for (auto [term, R] : {std::pair{f.term.get(), &R_ran}, std::pair{restored.get(), &R_restored}}) {
    term->prepare_step(next);
    term->set_auxiliary_offset(f.nx);
    Eigen::VectorXd z = Eigen::VectorXd::Zero(f.nx + term->auxiliary_count());
    z.head(f.nx) = x_1;
    term->initialize_auxiliaries(next, z);
    *R = Eigen::VectorXd::Zero(z.size());
    term->add(next, z, *R, nullptr);
  }
  ASSERT_EQ(R_ran.size(), R_restored.size());
  EXPECT_GT(R_ran.head(f.nx).norm(), 0);
  EXPECT_LE((R_ran - R_restored).norm(), 1e-12 * R_ran.norm());
}

class ContactOnRanks : public ::testing::TestWithParam<model::Scheme> {};

// Two ranks played in one process (ranks_test_utils.hpp).
TEST_P(ContactOnRanks, EachRankComputesItsSlaveNodesAndEveryRankGetsOneProcesssRows) {
  Fixture f(GetParam(), 5);
  if (GetParam() == model::Scheme::hht) {  // a t_n force of the last step's elements too (2.11)
    for (int i = f.nx; i < f.z.size(); ++i) f.z[i] = 1.0 + 0.1 * (i - f.nx);
    f.term->end_step(*f.step, f.z);
    f.term->prepare_step(*f.step);
    f.term->set_auxiliary_offset(f.nx);
  }
  ASSERT_EQ(f.term->elements().size(), 4u);
  test::expect_one_process_rows(test::play_two_ranks(*f.term, f.mesh, *f.step, f.z));
}

INSTANTIATE_TEST_SUITE_P(Schemes, ContactOnRanks,
                         ::testing::Values(model::Scheme::energy_momentum, model::Scheme::midpoint,
                                           model::Scheme::hht),
                         [](const auto& info) { return std::string(model::to_string(info.param)); });

TEST(ContactTerm, EachSchemeGetsTheTermOfItsForceRule) {
  const mesh::Mesh m = cube_over_plate();
  EXPECT_NE(dynamic_cast<MixedContactTerm*>(lagrange_term(m, pair(), model::Scheme::energy_momentum).get()),
            nullptr);
  for (const model::Scheme s :
       {model::Scheme::midpoint, model::Scheme::hht, model::Scheme::generalized_alpha})
    EXPECT_NE(dynamic_cast<NtsContactTerm*>(lagrange_term(m, pair(), s).get()), nullptr)
        << model::to_string(s);
}

}  // namespace
}  // namespace stoss::contact
