// The second-order forward number (second_order.hpp) that carries Σ_j λ_j ∂²g̃_j/∂x² (docs/theory.md (4.81)):
// its rules on a small function, and pair_gaps' gradient and weighted Hessian on a skewed, warped, partially
// overlapping face pair against central differences of the gaps in extended precision and against the nested
// dual numbers it replaced.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <tuple>

#include "core/contact/mortar/pair_derivatives.hpp"
#include "core/contact/mortar/second_order.hpp"

namespace stoss::contact::mortar {
namespace {

using Long = long double;

// f(x, y) = √(x y) / (x + 3) − y² against its derivatives by hand.
TEST(SecondOrder, ProductQuotientAndRootFollowTheChainRule) {
  const double x = 1.7, y = 0.6;
  using S = SecondOrder<2>;
  const S X = S::variable(x, 0), Y = S::variable(y, 1);
  const S f = sqrt(X * Y) / (X + 3.0) - Y * Y;
  const double r = std::sqrt(x * y), d = x + 3;
  const double r_x = 0.5 * y / r, r_y = 0.5 * x / r;
  const double r_xx = -0.25 * y * y / (r * r * r), r_yy = -0.25 * x * x / (r * r * r);
  const double r_xy = 0.5 / r - 0.25 * x * y / (r * r * r);
  EXPECT_DOUBLE_EQ(f.value(), r / d - y * y);
  EXPECT_NEAR(f.gradient()[0], r_x / d - r / (d * d), 1e-15);
  EXPECT_NEAR(f.gradient()[1], r_y / d - 2 * y, 1e-15);
  const Eigen::Matrix2d H = f.hessian();
  EXPECT_NEAR(H(0, 0), r_xx / d - 2 * r_x / (d * d) + 2 * r / (d * d * d), 1e-15);
  EXPECT_NEAR(H(0, 1), r_xy / d - r_y / (d * d), 1e-15);
  EXPECT_NEAR(H(1, 0), H(0, 1), 0);
  EXPECT_NEAR(H(1, 1), r_yy / d - 2, 1e-15);
}

// A slave face (normal −z, warped) and a master face (normal +z, warped) turned and shifted against it: they
// overlap partially (area 0.54 of about 1), in general position: the differences cross no vertex-edge change.
void skewed_pair(SegmentNodes& s, SegmentNodes& m) {
  s << 0, 0, 0.01, 0, 1.1, -0.02, 0.9, 1.0, 0.0, 1.0, -0.1, 0.015;
  m << 0.3, 0.2, -0.05, 1.4, 0.25, -0.03, 1.35, 1.3, -0.06, 0.25, 1.2, -0.02;
}

// Σ_j λ_j g̃_j in extended precision with coordinates a and b moved by ha and hb (an index −1 moves nothing).
Long weighted_gap(const SegmentNodes& s, const SegmentNodes& m, Multipliers kind,
                  const Eigen::Vector4d& lambda, int a, Long ha, int b, Long hb) {
  QuadNodes<Long> S, M;
  for (int K = 0; K < 4; ++K)
    for (int i = 0; i < 3; ++i) S[K][i] = s(K, i), M[K][i] = m(K, i);
  const auto move = [&](int index, Long h) {
    if (index < 0) return;
    (index < 12 ? S[index / 3][index % 3] : M[(index - 12) / 3][index % 3]) += h;
  };
  move(a, ha), move(b, hb);
  const FacePairIntegrals<Long> r = face_pair_integrals<Long>(S, M, kind);
  Long sum = 0;
  for (int j = 0; j < 4; ++j) sum += Long(lambda[j]) * r.gap[j];
  return sum;
}

class MortarSecondOrder : public ::testing::TestWithParam<Multipliers> {};
INSTANTIATE_TEST_SUITE_P(Kinds, MortarSecondOrder,
                         ::testing::Values(Multipliers::standard, Multipliers::dual));

// (4.80), (4.81) against central differences: gradient with h = 1e-6 (truncation ~1e-12), Hessian by the
// four-point formula with h = 1e-4 (truncation ~1e-8; round-off 1e-19 / h² = 1e-11), in long double.
TEST_P(MortarSecondOrder, GradientAndWeightedHessianMatchCentralDifferencesOfTheGaps) {
  const Multipliers kind = GetParam();
  SegmentNodes s, m;
  skewed_pair(s, m);
  const Eigen::Vector4d lambda(-1, -0.7, -1.3, -0.9);
  Matrix24 H;
  const PairGaps g = pair_gaps(s, m, kind, lambda, H);
  ASSERT_GT(g.area, 0.3);
  ASSERT_LT(g.area, 0.8) << "partial overlap";
  const Eigen::Matrix<double, 1, 24> force = lambda.transpose() * g.gradient;
  Eigen::Matrix<double, 1, 24> force_differences;
  const Long hg = 1e-6L;
  for (int a = 0; a < 24; ++a)
    force_differences[a] = static_cast<double>(
        (weighted_gap(s, m, kind, lambda, a, hg, -1, 0) - weighted_gap(s, m, kind, lambda, a, -hg, -1, 0)) /
        (2 * hg));
  Matrix24 H_differences;
  const Long h = 1e-4L;
  for (int a = 0; a < 24; ++a)
    for (int b = a; b < 24; ++b)
      H_differences(a, b) = H_differences(b, a) = static_cast<double>(
          (weighted_gap(s, m, kind, lambda, a, h, b, h) - weighted_gap(s, m, kind, lambda, a, h, b, -h) -
           weighted_gap(s, m, kind, lambda, a, -h, b, h) + weighted_gap(s, m, kind, lambda, a, -h, b, -h)) /
          (4 * h * h));
  const double gradient_error = (force - force_differences).norm() / force.norm();
  const double hessian_error = (H - H_differences).norm() / H.norm();
  std::printf("skewed pair: |λ·∂g̃ − central| / |λ·∂g̃| = %.1e, |H − central| / |H| = %.1e\n", gradient_error,
              hessian_error);
  EXPECT_LT(gradient_error, 1e-9);
  EXPECT_LT(hessian_error, 1e-6);
  EXPECT_LT((H - H.transpose()).norm(), 1e-15 * H.norm());
}

// The same pair through the nested forward dual numbers (forward over forward, the former machinery): the
// same gaps, gradient and Hessian to round-off.
TEST_P(MortarSecondOrder, EqualsNestedDualNumbersToRoundOff) {
  using Inner = Eigen::AutoDiffScalar<Eigen::Matrix<double, 24, 1>>;
  using Outer = Eigen::AutoDiffScalar<Eigen::Matrix<Inner, 24, 1>>;
  const Multipliers kind = GetParam();
  SegmentNodes s, m;
  skewed_pair(s, m);
  const Eigen::Vector4d lambda(-1, -0.7, -1.3, -0.9);
  QuadNodes<Outer> S, M;
  for (int K = 0; K < 4; ++K)
    for (int i = 0; i < 3; ++i)
      for (auto [x, value, index] :
           {std::tuple{&S[K][i], s(K, i), 3 * K + i}, std::tuple{&M[K][i], m(K, i), 12 + 3 * K + i}}) {
        *x = Outer(Inner(value, 24, index));
        x->derivatives() = Eigen::Matrix<Inner, 24, 1>::Constant(Inner(0.0));
        x->derivatives()[index] = Inner(1.0);
      }
  const FacePairIntegrals<Outer> r = face_pair_integrals<Outer>(S, M, kind);
  Matrix24 nested = Matrix24::Zero();
  Eigen::Matrix<double, 4, 24> nested_gradient;
  for (int j = 0; j < 4; ++j) {
    nested_gradient.row(j) = r.gap[j].value().derivatives().transpose();
    for (int a = 0; a < 24; ++a)
      nested.row(a) += lambda[j] * r.gap[j].derivatives()[a].derivatives().transpose();
  }
  Matrix24 H;
  const PairGaps g = pair_gaps(s, m, kind, lambda, H);
  // The gaps (1e-3) are sums of terms 50 times larger: round-off 1e-17 (measured 3e-18).
  for (int j = 0; j < 4; ++j) EXPECT_NEAR(g.gap[j], value_of(r.gap[j]), 1e-16);
  EXPECT_LT((g.gradient - nested_gradient).norm(), 1e-13 * nested_gradient.norm());
  EXPECT_LT((H - nested).norm(), 1e-13 * nested.norm());
}

}  // namespace
}  // namespace stoss::contact::mortar
