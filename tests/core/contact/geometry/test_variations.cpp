#include <gtest/gtest.h>

#include "core/contact/geometry/projection.hpp"
#include "core/contact/geometry/variations.hpp"
#include "tests/core/contact/contact_test_utils.hpp"

namespace stoss::contact {
namespace {
using test::fd_jacobian;
using test::fd_step;
using test::relative_error;

// Finite differences through the CPP (3.4): every perturbed state is re-projected, starting from
// the unperturbed ξ.
class GapVariationsFD : public ::testing::TestWithParam<unsigned> {
 protected:
  void SetUp() override {
    state = test::random_nts_state(GetParam());
    x = state.x();
    cpp = closest_point_projection(state.slave, state.nodes);
    ASSERT_TRUE(cpp.converged);
    v = gap_variations(cpp.frame, cpp.gap);
  }
  Projection project(const Vector15& z) const {
    const Projection p = closest_point_projection(slave_position(z), segment_nodes(z), cpp.xi);
    EXPECT_TRUE(p.converged);
    return p;
  }
  test::NtsState state;
  Vector15 x;
  Projection cpp;
  GapVariations v;
};

// Relative FD errors observed: ~1e-10 (N_s, D), ~1e-9 (∂n, ∂N_s); bound 1e-6 of §6.1.
constexpr double tolerance = 1e-6;

TEST_P(GapVariationsFD, GapGradient) {
  const auto gap = [&](const Vector15& z) { return Eigen::Matrix<double, 1, 1>(project(z).gap); };
  const RowVector15 fd = fd_jacobian(gap, x, fd_step);
  EXPECT_LT(relative_error(v.Ns.transpose(), fd), tolerance);
}

TEST_P(GapVariationsFD, XiGradient) {
  const auto xi = [&](const Vector15& z) { return project(z).xi; };
  EXPECT_LT(relative_error(v.D, fd_jacobian(xi, x, fd_step)), tolerance);
}

TEST_P(GapVariationsFD, TangentGradients) {
  const auto tau1 = [&](const Vector15& z) { return project(z).frame.tau1; };
  const auto tau2 = [&](const Vector15& z) { return project(z).frame.tau2; };
  EXPECT_LT(relative_error(v.dtau[0], fd_jacobian(tau1, x, fd_step)), tolerance);
  EXPECT_LT(relative_error(v.dtau[1], fd_jacobian(tau2, x, fd_step)), tolerance);
}

TEST_P(GapVariationsFD, NormalGradient) {
  const auto normal = [&](const Vector15& z) { return project(z).frame.normal; };
  EXPECT_LT(relative_error(v.dn, fd_jacobian(normal, x, fd_step)), tolerance);
}

TEST_P(GapVariationsFD, GapHessian) {
  const auto Ns = [&](const Vector15& z) {
    const Projection p = project(z);
    return gap_gradient(p.frame);
  };
  EXPECT_LT(relative_error(v.dNs, fd_jacobian(Ns, x, fd_step)), tolerance);
}

// ∂N_s/∂x is the Hessian of g_N: symmetric.
TEST_P(GapVariationsFD, GapHessianIsSymmetric) {
  EXPECT_LT((v.dNs - v.dNs.transpose()).norm(), 1e-12 * v.dNs.norm());
}

// D_α from its parts (3.7), and the gap gradient sums to zero over the nodes (translation).
TEST_P(GapVariationsFD, PartsAreConsistent) {
  const Eigen::Matrix2d A = projection_matrix(cpp.frame, cpp.gap * cpp.frame.normal);
  const Matrix2x15 rhs = tangent_variation(cpp.frame) + cpp.gap * normal_variation(cpp.frame);
  EXPECT_LT((A * v.D - rhs).norm(), 1e-14 * rhs.norm());
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int node = 0; node < 5; ++node) sum += v.Ns.segment<3>(3 * node);
  EXPECT_LT(sum.norm(), 1e-15);
}

INSTANTIATE_TEST_SUITE_P(Seeds, GapVariationsFD, ::testing::Values(1u, 2u, 3u, 4u));

}  // namespace
}  // namespace stoss::contact
