// The energy–momentum form of mortar contact (docs/theory.md §4.7.2): the discrete gradient of one face
// pair's weighted gaps is exact for their increments over the step (what makes a persistent contact do no
// work), its force has no net force and no net moment about the midpoint configuration (what keeps both
// momenta), a rigid step gets the midpoint gradient, and the tangent (4.88) and ∂w/∂x_{n+1} (4.86) match
// central differences.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdio>

#include "core/contact/mortar/frame_indifferent_gradient.hpp"

namespace stoss::contact::mortar {
namespace {

// A warped slave face (normal −z) and a warped master face turned and shifted against it, overlapping in part
// (as test_mortar_second_order.cpp's skewed pair).
Vector24 skewed_pair() {
  Vector24 x;
  x << 0, 0, 0.01, 0, 1.1, -0.02, 0.9, 1.0, 0.0, 1.0, -0.1, 0.015,            // slave
      0.3, 0.2, -0.05, 1.4, 0.25, -0.03, 1.35, 1.3, -0.06, 0.25, 1.2, -0.02;  // master
  return x;
}

SegmentNodes slave_of(const Vector24& x) {
  SegmentNodes s;
  for (int K = 0; K < 4; ++K) s.row(K) = x.segment<3>(3 * K).transpose();
  return s;
}
SegmentNodes master_of(const Vector24& x) {
  SegmentNodes m;
  for (int K = 0; K < 4; ++K) m.row(K) = x.segment<3>(12 + 3 * K).transpose();
  return m;
}

/// The pair after a step: turned by `angle` about an axis through (0.4, 0.3, 0), shifted, and deformed by
/// `strain` times a fixed pattern (the slave also pressed into the master by 0.05 `strain`).
Vector24 stepped(const Vector24& x, double angle, double strain) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()).matrix();
  const Eigen::Vector3d pivot(0.4, 0.3, 0), shift(0.05, -0.02, 0.03);
  Vector24 y;
  for (int a = 0; a < 8; ++a) {
    Eigen::Vector3d p = x.segment<3>(3 * a);
    p += strain * Eigen::Vector3d(0.3 * p.y(), -0.2 * p.x(), (a < 4 ? -0.05 : 0.0) + 0.1 * p.x() * p.y());
    y.segment<3>(3 * a) = R * (p - pivot) + pivot + shift;
  }
  return y;
}

struct Evaluated {
  PairGaps at_n, at_end, at_mid;
  Matrix24 H = Matrix24::Zero();
};

Evaluated evaluate(const Vector24& x_n, const Vector24& x_1, const Eigen::Vector4d& lambda) {
  Evaluated e;
  Matrix24 unused;
  e.at_n = pair_gaps(slave_of(x_n), master_of(x_n), Multipliers::dual);
  e.at_end = pair_gaps(slave_of(x_1), master_of(x_1), Multipliers::dual);
  const Vector24 mid = 0.5 * (x_n + x_1);
  e.at_mid = pair_gaps(slave_of(mid), master_of(mid), Multipliers::dual, lambda, e.H);
  return e;
}

PairDiscreteGradient gradient_of(const Vector24& x_n, const Vector24& x_1, const Eigen::Vector4d& lambda,
                                 bool with_tangent) {
  const Evaluated e = evaluate(x_n, x_1, lambda);
  return discrete_gradient({x_n, x_1, e.at_n.gap, e.at_end, e.at_mid, with_tangent ? &e.H : nullptr, 1.0},
                           lambda);
}

const Eigen::Vector4d lambda(-1, -0.7, -1.3, -0.9);

// G_j · Δ = g̃_j(x_{n+1}) − g̃_j(x_n) (4.87) where the midpoint gradient misses it by the step's third order;
// Σ_a G_j,a = 0 and Σ_a x_m,a × G_j,a = 0: the contact force keeps linear and angular momentum.
TEST(MortarDiscreteGradient, IsExactForTheGapIncrementsAndExertsNoNetForceOrMoment) {
  const Vector24 x_n = skewed_pair(), x_1 = stepped(x_n, 0.4, 0.3), mid = 0.5 * (x_n + x_1);
  const Evaluated e = evaluate(x_n, x_1, lambda);
  const PairDiscreteGradient dg = gradient_of(x_n, x_1, lambda, false);
  const Vector24 delta = x_1 - x_n;
  const Eigen::Vector4d increment = e.at_end.gap - e.at_n.gap;
  const double midpoint_miss = (e.at_mid.gradient * delta - increment).cwiseAbs().maxCoeff();
  const double miss = (dg.gradient * delta - increment).cwiseAbs().maxCoeff();
  std::printf("gap increments %.3e: midpoint gradient misses by %.1e, discrete gradient by %.1e\n",
              increment.cwiseAbs().maxCoeff(), midpoint_miss, miss);
  EXPECT_GT(midpoint_miss, 1e-5) << "the step is large enough for the midpoint form to miss";
  EXPECT_LT(miss, 1e-15);
  for (int j = 0; j < 4; ++j) {
    Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
    for (int a = 0; a < 8; ++a) {
      const Eigen::Vector3d G = dg.gradient.block<1, 3>(j, 3 * a).transpose();
      force += G, moment += Eigen::Vector3d(mid.segment<3>(3 * a)).cross(G);
    }
    const double scale = dg.gradient.row(j).norm();
    EXPECT_LT(force.norm(), 1e-14 * scale) << j;
    EXPECT_LT(moment.norm(), 1e-14 * scale) << j;
  }
}

// A rigid step (a finite rotation and a shift) has no deformation part: w = 0 to round-off, and the discrete
// gradient is the midpoint gradient, whose increments are then exact as well (both zero).
TEST(MortarDiscreteGradient, ARigidStepGetsTheMidpointGradient) {
  const Vector24 x_n = skewed_pair(), x_1 = stepped(x_n, 0.7, 0.0);
  EXPECT_LT(step_deformation(x_n, x_1).w.norm(), 1e-14);
  const Evaluated e = evaluate(x_n, x_1, lambda);
  const PairDiscreteGradient dg = gradient_of(x_n, x_1, lambda, false);
  EXPECT_EQ(dg.gradient, e.at_mid.gradient);
  EXPECT_LT((e.at_end.gap - e.at_n.gap).cwiseAbs().maxCoeff(), 1e-15);
}

// ∂w/∂x_{n+1} (4.86) and ∂(Σ λ_j G_j)/∂x_{n+1} (4.88) against central differences with h = 1e-6.
TEST(MortarDiscreteGradient, DerivativesMatchCentralDifferences) {
  const Vector24 x_n = skewed_pair(), x_1 = stepped(x_n, 0.3, 0.2);
  const double h = 1e-6;
  const StepDeformation deformation = step_deformation(x_n, x_1);
  const PairDiscreteGradient dg = gradient_of(x_n, x_1, lambda, true);
  Matrix24 dw, tangent;
  for (int b = 0; b < 24; ++b) {
    Vector24 plus = x_1, minus = x_1;
    plus[b] += h, minus[b] -= h;
    dw.col(b) = (step_deformation(x_n, plus).w - step_deformation(x_n, minus).w) / (2 * h);
    tangent.col(b) = ((lambda.transpose() * gradient_of(x_n, plus, lambda, false).gradient) -
                      (lambda.transpose() * gradient_of(x_n, minus, lambda, false).gradient))
                         .transpose() /
                     (2 * h);
  }
  const double dw_error = (deformation.derivative - dw).norm() / dw.norm();
  const double tangent_error = (dg.tangent - tangent).norm() / tangent.norm();
  std::printf("∂w/∂x: %.1e, tangent: %.1e (relative to central differences)\n", dw_error, tangent_error);
  EXPECT_LT(dw_error, 1e-8);
  EXPECT_LT(tangent_error, 1e-6);
}

}  // namespace
}  // namespace stoss::contact::mortar
