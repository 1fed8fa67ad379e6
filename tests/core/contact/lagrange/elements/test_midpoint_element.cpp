#include <gtest/gtest.h>

#include "core/contact/lagrange/elements/midpoint_element.hpp"
#include "tests/core/contact/contact_test_utils.hpp"

namespace stoss::contact {
namespace {
using test::fd_jacobian;
using test::fd_step;
using test::relative_error;

class MidpointElement : public ::testing::TestWithParam<unsigned> {
 protected:
  void SetUp() override {
    const test::NtsState s = test::random_nts_state(GetParam());
    std::mt19937 rng(GetParam() + 300);
    x_n = s.x();
    x_1 = x_n + test::random_vector<15>(rng, 0.03);
    lambda = test::random_vector<1>(rng)[0];
    e = at(x_1, lambda);
    ASSERT_TRUE(e.converged);
  }
  MidpointResult at(const Vector15& x, double l) const {
    return midpoint_element(x_n, x, l, f3, h, xi_start);
  }
  Vector15 x_n, x_1;
  double lambda = 0, f3 = 0.02, h = 0.01;
  Eigen::Vector2d xi_start{0, 0};
  MidpointResult e;
};

// Tangent blocks of §4.2 against central differences through both CPPs; §6.1 bound 1e-6.
TEST_P(MidpointElement, KxxMatchesFiniteDifferences) {
  const auto Rx = [&](const Vector15& x) { return at(x, lambda).Rx; };
  EXPECT_LT(relative_error(e.Kxx, fd_jacobian(Rx, x_1, fd_step)), 1e-6);
}

TEST_P(MidpointElement, KxlMatchesFiniteDifferences) {
  const auto Rx = [&](const Eigen::Matrix<double, 1, 1>& l) { return at(x_1, l[0]).Rx; };
  EXPECT_LT(relative_error(e.Kxl, fd_jacobian(Rx, Eigen::Matrix<double, 1, 1>(lambda), fd_step)), 1e-6);
}

TEST_P(MidpointElement, KlxMatchesFiniteDifferences) {
  const auto Rl = [&](const Vector15& x) { return Eigen::Matrix<double, 1, 1>(at(x, lambda).Rl); };
  EXPECT_LT(relative_error(e.Klx, fd_jacobian(Rl, x_1, fd_step)), 1e-6);
}

TEST_P(MidpointElement, ConstraintIsGapMinusTarget) {
  const Projection p = closest_point_projection(slave_position(x_1), segment_nodes(x_1));
  EXPECT_NEAR(e.Rl, p.gap - f3, 1e-14);
}

// L and J (4.2): Σ N_s entries = 0, and the torque (x_s − y) × n g-form vanishes at x_m.
TEST_P(MidpointElement, ForceHasNoNetForceOrTorque) {
  const Vector15 x_m = 0.5 * (x_n + x_1);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  for (int node = 0; node < 5; ++node) {
    sum += e.Rx.segment<3>(3 * node);
    torque += x_m.segment<3>(3 * node).cross(e.Rx.segment<3>(3 * node));
  }
  EXPECT_LT(sum.norm(), 1e-15 * e.Rx.norm() * 10);
  EXPECT_LT(torque.norm(), 1e-12 * e.Rx.norm() * x_m.norm());
}

INSTANTIATE_TEST_SUITE_P(Seeds, MidpointElement, ::testing::Values(1u, 2u, 3u, 4u));

}  // namespace
}  // namespace stoss::contact
