// The frictional penalty element on a smooth patch (docs/smooth_master_surface.md §3.8, docs/theory.md
// §5.2) shall have a tangent that matches central differences of its force, in a face interior, on an
// edge, at a surface rim, near an extraordinary vertex and on a bilinear face, in stick, in slip and
// without friction, for both normal rules; its force shall carry no net force or torque; on a bilinear
// face it shall equal the faceted element; and the third derivatives of the patch it needs shall match
// differences of the second.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>
#include <string>
#include <tuple>

#include "core/contact/geometry/local_patch.hpp"
#include "core/contact/geometry/patch_projection.hpp"
#include "core/contact/penalty/patch_penalty_element.hpp"
#include "core/contact/penalty/penalty_element.hpp"
#include "tests/core/contact/smooth_test_utils.hpp"

namespace stoss::contact {
namespace {

constexpr double stiffness = 1e3;

/// Friction behaviour of a case: μ p = ratio ‖t^tr‖ (ratio > 1 sticks, < 1 slips); 0: no friction.
struct Friction {
  const char* name;
  double ratio;
};

/// How the step's traction and geometry are evaluated: a normal rule at x_m, or static steps' x_{n+1}.
struct Evaluation {
  const char* name;
  NormalRule rule;
  bool at_end;  ///< static steps (docs/theory.md §5b.6)
};

class PatchPenaltyElement
    : public ::testing::TestWithParam<std::tuple<test::PatchCase, Friction, Evaluation, double>> {
 protected:
  void SetUp() override {
    const auto& [c, friction, evaluation, g_n] = GetParam();
    const test::PickedPatch picked = test::pick(c);
    const TensorPatch& patch = picked.patch;
    const PatchFrame on = patch_frame(patch, picked.grid.x, picked.xi);
    local = local_patch(patch);
    x_n.resize(3 + 3 * patch.size());
    x_n.head<3>() = on.y + g_n * on.normal;
    for (int K = 0; K < patch.size(); ++K)
      x_n.segment<3>(3 + 3 * K) = picked.grid.x.segment<3>(3 * patch.nodes[K]);
    std::mt19937 rng(7);
    std::normal_distribution<double> normal(0, 1);
    x_1 = x_n;
    for (Eigen::Index i = 0; i < x_1.size(); ++i) x_1[i] += 0.004 * normal(rng);
    x_1.head<3>() += -0.03 * on.normal + 0.02 * on.tau1 - 0.01 * on.tau2;  // presses in and slides
    history.traction = 4.0 * on.tau1.normalized() - 2.5 * on.tau2.normalized();
    xi_start = picked.xi;
    size = picked.grid.spacing;
    p = {stiffness, friction.ratio > 0 ? stiffness : 0.0, 1e12, evaluation.rule};
    p.at_end = evaluation.at_end;
    if (friction.ratio > 0) {
      const PatchPenaltyResult stick = at(x_1);
      const double norm = std::sqrt(stick.traction.dot(stick.at_m.frame.metric_inv * stick.traction));
      p.friction = friction.ratio * norm / -stick.normal_traction;
    } else {
      p.friction = 0;
    }
    r = at(x_1);
  }

  PatchPenaltyResult at(const Eigen::VectorXd& x) const {
    return patch_penalty_element(local, x_n, x, history, p, xi_start, size);
  }

  TensorPatch local;
  Eigen::VectorXd x_n, x_1;
  FrictionHistory history;
  Eigen::Vector2d xi_start;
  double size = 0;
  PenaltyParameters p;
  PatchPenaltyResult r;
};

TEST_P(PatchPenaltyElement, TangentMatchesCentralDifferences) {
  ASSERT_TRUE(r.closed);
  ASSERT_EQ(r.slip, std::get<1>(GetParam()).ratio > 0 && std::get<1>(GetParam()).ratio < 1);
  const Eigen::Index n = x_1.size();
  Eigen::MatrixXd fd(n, n);
  const double eps = 1e-6;
  for (Eigen::Index j = 0; j < n; ++j) {
    Eigen::VectorXd up = x_1, down = x_1;
    up[j] += eps, down[j] -= eps;
    fd.col(j) = (at(up).force - at(down).force) / (2 * eps);
  }
  EXPECT_LT((r.tangent - fd).norm(), 1e-6 * fd.norm()) << (r.tangent - fd).cwiseAbs().maxCoeff();
}

// The force is a discrete gradient (docs/smooth_master_surface.md (3.9)): its work over the step is
// t_N Δg_N + t_α Δξ^α exactly (1e-12), so the "dd" rule's W_N and the Coulomb law keep H + D. Static steps'
// element does that work on a virtual displacement at x_{n+1} (docs/theory.md §5b.6): F = t_N ∂g_N + t_α ∂ξ^α
// there, against central differences of the CPP at x_{n+1}, 1e-6 relative.
TEST_P(PatchPenaltyElement, WorkIsTractionTimesTheChangeOfGapAndCoordinates) {
  ASSERT_TRUE(r.closed);
  if (p.at_end) {
    const double eps = 1e-6;
    Eigen::VectorXd virtual_work(x_1.size());
    for (Eigen::Index j = 0; j < x_1.size(); ++j) {
      Eigen::VectorXd up = x_1, down = x_1;
      up[j] += eps, down[j] -= eps;
      const PatchPenaltyResult u = at(up), d = at(down);
      virtual_work[j] =
          (r.normal_traction * (u.at_1.gap - d.at_1.gap) + r.traction.dot(u.at_1.xi - d.at_1.xi)) / (2 * eps);
    }
    EXPECT_LT((r.force - virtual_work).norm(), 1e-6 * r.force.norm());
    return;
  }
  const double work = r.force.dot(x_1 - x_n);
  const double expected =
      r.normal_traction * (r.at_1.gap - r.at_n.gap) + r.traction.dot(r.at_1.xi - r.at_n.xi);
  EXPECT_NEAR(work, expected, 1e-12 * r.force.norm() * (x_1 - x_n).norm());
}

// Σ_nodes F = 0 and Σ x_m × F = 0 (the penalty law conserves L and J, §5.1), 1e-12 relative; about
// x_{n+1} for static steps' element.
TEST_P(PatchPenaltyElement, ForceHasNoNetForceOrTorqueAtTheMidpoint) {
  ASSERT_TRUE(r.closed);
  const Eigen::VectorXd x_m = p.at_end ? x_1 : Eigen::VectorXd(0.5 * (x_n + x_1));
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < x_m.size(); i += 3) {
    sum += r.force.segment<3>(i);
    torque += x_m.segment<3>(i).cross(r.force.segment<3>(i));
  }
  EXPECT_LT(sum.norm(), 1e-12 * r.force.norm());
  EXPECT_LT(torque.norm(), 1e-12 * r.force.norm() * x_m.norm());
}

std::string case_name(const ::testing::TestParamInfo<PatchPenaltyElement::ParamType>& info) {
  const auto& [c, friction, evaluation, g_n] = info.param;
  return std::string(c.name) + "_" + friction.name + "_" + evaluation.name +
         (g_n > 0 ? "_touchdown" : "_pressed");
}

INSTANTIATE_TEST_SUITE_P(
    Cases, PatchPenaltyElement,
    ::testing::Combine(::testing::Values(test::PatchCase{"interior", 1, 2, {0.2, -0.3}},
                                         test::PatchCase{"on_edge", 1, 1, {0.98, 0.1}},
                                         test::PatchCase{"corner", 1, 1, {0.97, -0.99}},
                                         test::PatchCase{"rim", 0, 2, {-0.9, 0.3}},
                                         test::PatchCase{"bilinear", 1, 1, {0.3, 0.4}, true},
                                         test::PatchCase{"extraordinary", -1, -1, {0.1, 0.06}, false, true}),
                       ::testing::Values(Friction{"stick", 2.0}, Friction{"slip", 0.5},
                                         Friction{"frictionless", 0}),
                       ::testing::Values(Evaluation{"dd", NormalRule::discrete_derivative, false},
                                         Evaluation{"mid", NormalRule::midpoint, false},
                                         Evaluation{"end", NormalRule::discrete_derivative, true}),
                       ::testing::Values(0.01, -0.005)),
    case_name);

// On a flat bilinear face that stays still, where g_N and ξ are affine in the slave's position and the
// midpoint gradients are already discrete gradients, the patch element's force is the faceted element's
// force of §5.2 to 1e-12 (their tangents differ: the correction's derivative in the master directions,
// where g_N is not affine, is not zero).
TEST(PatchPenaltyElementOnBilinearFace, EqualsTheFacetedElement) {
  test::PickedPatch picked{test::Grid::flat(3, 3, 0.25), {}, {0.3, 0.4}};
  picked.patch = bilinear_patch(picked.grid.faces[picked.grid.face(1, 1)]);
  const PatchFrame on = patch_frame(picked.patch, picked.grid.x, picked.xi);
  Vector15 x_n, x_1;
  x_n.head<3>() = on.y - 0.004 * on.normal;
  for (int K = 0; K < 4; ++K) x_n.segment<3>(3 + 3 * K) = picked.grid.x.segment<3>(3 * picked.patch.nodes[K]);
  x_1 = x_n;
  x_1.head<3>() += -0.01 * on.normal + 0.03 * on.tau1;
  FrictionHistory history;
  history.traction = 2.0 * on.tau2;
  const PenaltyParameters p{stiffness, stiffness, 0.3, NormalRule::discrete_derivative};
  const PenaltyResult faceted = penalty_element(x_n, x_1, history, p, picked.xi);
  const PatchPenaltyResult smooth =
      patch_penalty_element(local_patch(picked.patch), x_n, x_1, history, p, picked.xi, picked.grid.spacing);
  ASSERT_TRUE(faceted.closed && smooth.closed);
  EXPECT_TRUE(faceted.slip && smooth.slip);
  EXPECT_LT((smooth.force - faceted.force).norm(), 1e-12 * faceted.force.norm());
}

// N_{K,αβγ} against central differences of N_{K,αβ}, on a regular patch and near an extraordinary vertex.
TEST(PatchThirdDerivatives, MatchCentralDifferencesOfTheCurvatures) {
  for (const test::PatchCase& c : {test::PatchCase{"interior", 1, 2, {0.2, -0.3}},
                                   test::PatchCase{"extraordinary", -1, -1, {0.3, 0.2}, false, true}}) {
    const test::PickedPatch picked = test::pick(c);
    const BasisThirdDerivatives d3 = patch_third_derivatives(picked.patch, picked.xi);
    const double h = 1e-6;
    const Eigen::Vector2d e1(h, 0), e2(0, h);
    const BasisCurvatures p1 = patch_curvatures(picked.patch, picked.xi + e1),
                          m1 = patch_curvatures(picked.patch, picked.xi - e1);
    const BasisCurvatures p2 = patch_curvatures(picked.patch, picked.xi + e2),
                          m2 = patch_curvatures(picked.patch, picked.xi - e2);
    const double scale = d3.N111.norm() + d3.N222.norm();
    EXPECT_LT((d3.N111 - (p1.N11 - m1.N11) / (2 * h)).norm(), 1e-6 * scale) << c.name;
    EXPECT_LT((d3.N112 - (p1.N12 - m1.N12) / (2 * h)).norm(), 1e-6 * scale) << c.name;
    EXPECT_LT((d3.N122 - (p2.N12 - m2.N12) / (2 * h)).norm(), 1e-6 * scale) << c.name;
    EXPECT_LT((d3.N222 - (p2.N22 - m2.N22) / (2 * h)).norm(), 1e-6 * scale) << c.name;
  }
}

}  // namespace
}  // namespace stoss::contact
