#include <gtest/gtest.h>

#include <tuple>

#include "core/contact/lagrange/constraints.hpp"
#include "core/contact/lagrange/discrete_gradient.hpp"
#include "core/contact/lagrange/invariants.hpp"
#include "tests/core/contact/contact_test_utils.hpp"

namespace stoss::contact {
namespace {
using test::fd_jacobian;
using test::fd_step;
using test::relative_error;

// π_a from a random mixed state, π_b = π(q_a + δq) with |δq| ~ scale (0: π_b = π_a).
struct InvariantPair {
  Vector17 a, b;
};

InvariantPair invariant_pair(unsigned seed, double scale) {
  const test::MixedState m = test::random_mixed_state(seed);
  std::mt19937 rng(seed + 500);
  const Vector20 q_b = m.q_n + test::random_vector<20>(rng, scale);
  return {invariants(m.q_n, m.f3), invariants(q_b, m.f3)};
}

Vector6 subtraction_defect(const Vector17& a, const Vector17& b) {
  return constraints(b) - constraints(a) - constraint_gradient(0.5 * (a + b)) * (b - a);
}

bool finite(const DiscreteGradient& dg) {
  bool ok = dg.value.allFinite();
  for (const Matrix17& d : dg.derivative) ok = ok && d.allFinite();
  return ok;
}

using Case = std::tuple<unsigned, double>;  // seed, |δq|

class DefectClosedForm : public ::testing::TestWithParam<Case> {};

// (4.7) against the subtraction form, for δ moderate enough that subtraction is still accurate.
TEST_P(DefectClosedForm, MatchesSubtractionForm) {
  const auto [seed, scale] = GetParam();
  const InvariantPair p = invariant_pair(seed, scale);
  const Vector6 closed = discrete_gradient_defect(0.5 * (p.a + p.b), p.b - p.a);
  EXPECT_LT((closed - subtraction_defect(p.a, p.b)).cwiseAbs().maxCoeff(), 1e-14);
}

INSTANTIATE_TEST_SUITE_P(Moderate, DefectClosedForm,
                         ::testing::Combine(::testing::Values(1u, 2u, 3u),
                                            ::testing::Values(0.3, 0.05, 1e-3)));

class Directional : public ::testing::TestWithParam<Case> {};

// g(π_b) − g(π_a) = ∇̄g δ (4.6), including |δ| = 1e-10 and δ = 0. Bound: 1e-13 × max(1, |Δg|)
// (g is O(1) here; for tiny δ the reference Δg itself carries round-off of order 1e-16).
TEST_P(Directional, PropertyHoldsToRoundOff) {
  const auto [seed, scale] = GetParam();
  const InvariantPair p = invariant_pair(seed, scale);
  const DiscreteGradient dg = discrete_gradient(p.a, p.b);
  ASSERT_TRUE(finite(dg));
  const Vector6 dg_exact = constraints(p.b) - constraints(p.a);
  const double error = (dg.value * (p.b - p.a) - dg_exact).norm();
  EXPECT_LT(error, 1e-13 * std::max(1.0, dg_exact.norm()));
  if (scale == 0) {
    EXPECT_EQ(dg.value, constraint_gradient(p.a));
  } else {
    EXPECT_LT(relative_error(dg.value, constraint_gradient(0.5 * (p.a + p.b))), std::max(10 * scale, 1e-12));
  }
}

INSTANTIATE_TEST_SUITE_P(Scales, Directional,
                         ::testing::Combine(::testing::Values(1u, 2u, 3u),
                                            ::testing::Values(0.3, 0.05, 1e-3, 1e-7, 1e-10, 1e-13, 0.0)));

// |δ| = 1e-10 down to 1e-200, chosen in π directly (ξ entries included): finite and directional.
class TinyDelta : public ::testing::TestWithParam<double> {};

TEST_P(TinyDelta, StaysFiniteAndDirectional) {
  const InvariantPair p = invariant_pair(9, 0.0);
  std::mt19937 rng(9);
  Vector17 delta = test::random_vector<17>(rng);
  delta[6] = 0;  // π7 = f_3 is a parameter
  delta *= GetParam() / delta.norm();
  const DiscreteGradient dg = discrete_gradient(p.a, p.a + delta);
  ASSERT_TRUE(finite(dg));
  const Vector6 dg_exact = constraints(p.a + delta) - constraints(p.a);
  EXPECT_LT((dg.value * delta - dg_exact).norm(), 1e-13 * std::max(1.0, dg_exact.norm()));
  EXPECT_LT(relative_error(dg.value, constraint_gradient(p.a + 0.5 * delta)), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Magnitudes, TinyDelta, ::testing::Values(1e-10, 1e-13, 1e-100, 1e-170, 1e-200));

class DiscreteGradientDerivative : public ::testing::TestWithParam<Case> {};

// (4.8) against FD of ∇̄g w.r.t. π_b; at δ = 0 it is ½H_k(π_m).
TEST_P(DiscreteGradientDerivative, MatchesFiniteDifferences) {
  const auto [seed, scale] = GetParam();
  const InvariantPair p = invariant_pair(seed, scale);
  const DiscreteGradient dg = discrete_gradient(p.a, p.b);
  for (int k = 0; k < 6; ++k) {
    const auto row = [&](const Vector17& b) {
      return Vector17(discrete_gradient(p.a, b).value.row(k).transpose());
    };
    const Matrix17 fd = fd_jacobian(row, p.b, fd_step);
    if (fd.norm() < 1e-12) {  // g_4 is linear in π
      EXPECT_LT(dg.derivative[k].norm(), 1e-12);
      continue;
    }
    EXPECT_LT(relative_error(dg.derivative[k], fd), 1e-6) << "k = " << k;
  }
  if (scale == 0) {
    const std::array<Matrix17, 6> H = constraint_hessians(p.a);
    for (int k = 0; k < 6; ++k) EXPECT_EQ(dg.derivative[k], 0.5 * H[k]);
  }
}

INSTANTIATE_TEST_SUITE_P(Scales, DiscreteGradientDerivative,
                         ::testing::Combine(::testing::Values(1u, 2u, 3u),
                                            ::testing::Values(0.3, 0.05, 0.0)));

}  // namespace
}  // namespace stoss::contact
