#include <gtest/gtest.h>

#include "core/contact/lagrange/invariants.hpp"
#include "tests/core/contact/contact_test_utils.hpp"

namespace stoss::contact {
namespace {
using test::fd_jacobian;
using test::fd_step;
using test::relative_error;

class Invariants : public ::testing::TestWithParam<unsigned> {
 protected:
  void SetUp() override { m = test::random_mixed_state(GetParam()); }
  test::MixedState m;
};

TEST_P(Invariants, JacobianMatchesFiniteDifferences) {
  const auto pi = [&](const Vector20& q) { return invariants(q, m.f3); };
  EXPECT_LT(relative_error(invariant_jacobian(m.q_n), fd_jacobian(pi, m.q_n, fd_step)), 1e-9);
}

// π is at most quadratic: π(q_b) − π(q_a) = Dπ(q_m)(q_b − q_a) exactly.
TEST_P(Invariants, MidpointIdentityIsExact) {
  const Vector17 dpi = invariants(m.q_1, m.f3) - invariants(m.q_n, m.f3);
  const Vector17 via_jacobian = invariant_jacobian(0.5 * (m.q_n + m.q_1)) * (m.q_1 - m.q_n);
  EXPECT_LT(relative_error(via_jacobian, dpi), 1e-13);
}

// Σ μ_k A_k is the derivative of Dπᵀμ (exact for a quadratic π: FD error is round-off only).
TEST_P(Invariants, HessianContractionMatchesFiniteDifferences) {
  std::mt19937 rng(GetParam());
  const Vector17 mu = test::random_vector<17>(rng);
  const auto force = [&](const Vector20& q) { return Vector20(invariant_jacobian(q).transpose() * mu); };
  const Matrix20 A = invariant_hessian_contraction(mu);
  EXPECT_LT(relative_error(A, fd_jacobian(force, m.q_n, fd_step)), 1e-9);
  EXPECT_LT((A - A.transpose()).norm(), 1e-15);
}

// Rotating positions and d and translating positions leaves π unchanged.
TEST_P(Invariants, InvariantUnderRotationAndTranslation) {
  std::mt19937 rng(GetParam() + 77);
  const Eigen::Matrix3d R = test::random_rotation(rng);
  const Eigen::Vector3d t = test::random_vector<3>(rng);
  Vector20 q = m.q_n;
  for (int node = 0; node < 5; ++node) q.segment<3>(3 * node) = R * m.q_n.segment<3>(3 * node) + t;
  q.segment<3>(MixedLayout::director) = R * m.q_n.segment<3>(MixedLayout::director);
  EXPECT_LT(relative_error(invariants(q, m.f3), invariants(m.q_n, m.f3)), 1e-13);
}

TEST_P(Invariants, MatchTheTable) {
  const Vector20& q = m.q_n;
  const Eigen::Vector3d xs = q.segment<3>(0), y1 = q.segment<3>(3), d = q.segment<3>(15);
  const Eigen::Vector3d r = xs - y1;
  const Eigen::Vector3d e[3] = {q.segment<3>(6) - y1, q.segment<3>(9) - y1, q.segment<3>(12) - y1};
  const Vector17 pi = invariants(q, m.f3);
  EXPECT_DOUBLE_EQ(pi[0], r.dot(d));
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(pi[1 + i], e[i].dot(d));
    EXPECT_DOUBLE_EQ(pi[8 + i], e[i].dot(r));
  }
  EXPECT_EQ(pi[4], q[18]);
  EXPECT_EQ(pi[5], q[19]);
  EXPECT_EQ(pi[6], m.f3);
  EXPECT_DOUBLE_EQ(pi[7], d.dot(d));
  const int pairs[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
  for (int l = 0; l < 6; ++l) EXPECT_DOUBLE_EQ(pi[11 + l], e[pairs[l][0]].dot(e[pairs[l][1]]));
}

INSTANTIATE_TEST_SUITE_P(Seeds, Invariants, ::testing::Values(1u, 2u, 3u, 4u));

}  // namespace
}  // namespace stoss::contact
