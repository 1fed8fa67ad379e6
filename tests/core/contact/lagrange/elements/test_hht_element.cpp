// The HHT-α contact element (docs/theory.md (2.11) with the NTS gap of §3): tangent blocks against
// central differences through the CPP (§6.1 bound 1e-6), and the force structure that keeps L.
#include <gtest/gtest.h>

#include "core/contact/geometry/variations.hpp"
#include "core/contact/lagrange/elements/hht_element.hpp"
#include "tests/core/contact/contact_test_utils.hpp"

namespace stoss::contact {
namespace {
using test::fd_jacobian;
using test::fd_step;
using test::relative_error;

class HhtElement : public ::testing::TestWithParam<unsigned> {
 protected:
  void SetUp() override {
    const test::NtsState s = test::random_nts_state(GetParam());
    std::mt19937 rng(GetParam() + 500);
    x_1 = s.x() + test::random_vector<15>(rng, 0.03);
    lambda = test::random_vector<1>(rng)[0];
    e = at(x_1, lambda);
    ASSERT_TRUE(e.converged);
  }
  HhtElementResult at(const Vector15& x, double l) const {
    return hht_element(x, l, f3, h, 1 + alpha, xi_start);
  }
  Vector15 x_1;
  double lambda = 0, f3 = 0.02, h = 0.01, alpha = -0.05;
  Eigen::Vector2d xi_start{0, 0};
  HhtElementResult e;
};

TEST_P(HhtElement, KxxMatchesFiniteDifferences) {
  const auto Rx = [&](const Vector15& x) { return at(x, lambda).Rx; };
  EXPECT_LT(relative_error(e.Kxx, fd_jacobian(Rx, x_1, fd_step)), 1e-6);
}

TEST_P(HhtElement, KxlMatchesFiniteDifferences) {
  const auto Rx = [&](const Eigen::Matrix<double, 1, 1>& l) { return at(x_1, l[0]).Rx; };
  EXPECT_LT(relative_error(e.Kxl, fd_jacobian(Rx, Eigen::Matrix<double, 1, 1>(lambda), fd_step)), 1e-6);
}

TEST_P(HhtElement, KlxMatchesFiniteDifferences) {
  const auto Rl = [&](const Vector15& x) { return Eigen::Matrix<double, 1, 1>(at(x, lambda).Rl); };
  EXPECT_LT(relative_error(e.Klx, fd_jacobian(Rl, x_1, fd_step)), 1e-6);
}

// (2.11): the constraint is g_N(x_{n+1}) − f_3 and the t_{n+1} force is h (1+α) λ N_s(x_{n+1}).
TEST_P(HhtElement, ResidualIsTheWeightedForceAndTheGapAtTheEnd) {
  const Projection p = closest_point_projection(slave_position(x_1), segment_nodes(x_1));
  EXPECT_NEAR(e.Rl, p.gap - f3, 1e-14);
  const Vector15 force = hht_element_force(x_1, lambda, xi_start);
  EXPECT_LT(relative_error(e.Rx, h * (1 + alpha) * force), 1e-14);
}

// Linear momentum: the entries of λ N_s sum to zero per direction, at x_{n+1} and for the t_n part.
TEST_P(HhtElement, ForceHasNoNetForce) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int node = 0; node < 5; ++node) sum += e.Rx.segment<3>(3 * node);
  EXPECT_LT(sum.norm(), 1e-14 * e.Rx.norm());
}

INSTANTIATE_TEST_SUITE_P(Seeds, HhtElement, ::testing::Values(1u, 2u, 3u, 4u));

}  // namespace
}  // namespace stoss::contact
