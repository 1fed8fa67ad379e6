// Tangents of the mortar kernel at ±1e-12 around the clip polygon's topology changes (issue 24 §6,
// docs/theory.md §4.7, (4.70), (4.80), (4.81)): a master vertex on a slave edge, coincident vertices,
// parallel (collinear) edges, and a slave face half outside the master with its edges on the master's rim.
// Flat faces 0.05 apart, so the rule (4.74) is exact and every difference is the kernel's. Where the overlap
// has a kink (parallel edges), the derivative on each side is its own: the central differences use h = δ/10
// so that they stay on the side of δ; at δ = 0 the kernel must give one of the two one-sided derivatives, not
// a mixture.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <functional>
#include <unsupported/Eigen/AutoDiff>

#include "core/contact/mortar/pair_derivatives.hpp"

namespace stoss::contact::mortar {
namespace {

using Jacobian = Eigen::Matrix<double, 4, 24>;

SegmentNodes quad(const double (&xy)[4][2], double z, bool down, double angle) {
  SegmentNodes n;
  const double c = std::cos(angle), s = std::sin(angle);
  for (int K = 0; K < 4; ++K) {
    const int k = down ? (4 - K) % 4 : K;  // down: clockwise in xy, outward normal −z
    n.row(K) << c * xy[k][0] - s * xy[k][1], s * xy[k][0] + c * xy[k][1], z;
  }
  return n;
}

// A configuration of one slave face (normal −z, at z = 0.05) over one master face (normal +z, at z = 0), the
// topology change at δ = 0, all turned by `angle` about z (so that "collinear" holds to round-off only).
struct Configuration {
  const char* name;
  std::function<void(double delta, double (&s)[4][2], double (&m)[4][2])> make;
};

void faces(const Configuration& c, double delta, double angle, SegmentNodes& s, SegmentNodes& m) {
  double sx[4][2], mx[4][2];
  c.make(delta, sx, mx);
  s = quad(sx, 0.05, true, angle);
  m = quad(mx, 0.0, false, angle);
}

void set(double (&p)[4][2], double x0, double y0, double x1, double y1, double x2, double y2, double x3,
         double y3) {
  const double v[4][2] = {{x0, y0}, {x1, y1}, {x2, y2}, {x3, y3}};
  for (int k = 0; k < 4; ++k) p[k][0] = v[k][0], p[k][1] = v[k][1];
}

const Configuration configurations[] = {
    {"master vertex on a slave edge",
     [](double d, double (&s)[4][2], double (&m)[4][2]) {
       set(s, 0, 0, 1, 0, 1, 1, 0, 1);
       set(m, 0.4, 0.1, 1 + d, 0.5, 0.6, 1.1, 0.05, 0.7);  // no other vertex on an edge
     }},
    {"coincident vertices (a master corner on a slave corner)",
     [](double d, double (&s)[4][2], double (&m)[4][2]) {
       set(s, 0, 0, 1, 0, 1, 1, 0, 1);
       set(m, 0.4, 0.2, 1.3, 0.6, 1 + d, 1 + d, 0.5, 1.3);
     }},
    {"parallel edges (a master edge on a slave edge)",
     [](double d, double (&s)[4][2], double (&m)[4][2]) {
       set(s, 0, 0, 1, 0, 1, 1, 0, 1);
       set(m, 0.3, 0.2, 1 + d, 0.2, 1 + d, 0.8, 0.3, 0.8);
     }},
    {"coincident corners and parallel edges (matching meshes)",
     [](double d, double (&s)[4][2], double (&m)[4][2]) {
       set(s, 0, 0, 1, 0, 1, 1, 0, 1);
       set(m, 0.3, 0.2, 1 + d, 0.2, 1 + d, 1 + d, 0.3, 1 + d);
     }},
    {"slave face half outside, its edges on the master's rim",
     [](double d, double (&s)[4][2], double (&m)[4][2]) {
       set(s, -0.5, -d, 0.5, -d, 0.5, 1 + d, -0.5, 1 + d);
       set(m, 0, 0, 1, 0, 1, 1, 0, 1);
     }},
};

// The kernel in extended precision, coordinate c moved by h (exactly, in long double): the references are
// central differences in long double, whose round-off (~1e-21 / h) is far below the double kernel's.
using Long = long double;
using LongDual = Eigen::AutoDiffScalar<Eigen::Matrix<Long, 24, 1>>;

template <class T, class Make>
FacePairIntegrals<T> moved(const SegmentNodes& s, const SegmentNodes& m, Multipliers kind, int c, Long h,
                           Make make) {
  QuadNodes<T> qs, qm;
  for (int K = 0; K < 4; ++K)
    for (int i = 0; i < 3; ++i) {
      const int cs = 3 * K + i, cm = 12 + 3 * K + i;
      qs[K][i] = make(Long(s(K, i)) + (c == cs ? h : Long(0)), cs);
      qm[K][i] = make(Long(m(K, i)) + (c == cm ? h : Long(0)), cm);
    }
  return face_pair_integrals<T>(qs, qm, kind);
}

Eigen::Matrix<Long, 4, 1> long_gaps(const SegmentNodes& s, const SegmentNodes& m, Multipliers kind, int c,
                                    Long h) {
  return moved<Long>(s, m, kind, c, h, [](Long x, int) { return x; }).gap;
}

// λ · ∂g̃/∂x in extended precision (dual numbers over long double).
Eigen::Matrix<Long, 24, 1> long_force(const SegmentNodes& s, const SegmentNodes& m, Multipliers kind,
                                      const Eigen::Vector4d& lambda, int c, Long h) {
  const FacePairIntegrals<LongDual> r =
      moved<LongDual>(s, m, kind, c, h, [](Long x, int index) { return LongDual(x, 24, index); });
  Eigen::Matrix<Long, 24, 1> f = Eigen::Matrix<Long, 24, 1>::Zero();
  for (int j = 0; j < 4; ++j)
    if (r.gap[j].derivatives().size() == 24) f += Long(lambda[j]) * r.gap[j].derivatives();
  return f;
}

template <class F>
Eigen::MatrixXd differences(int rows, Long h, F f) {
  Eigen::MatrixXd J(rows, 24);
  for (int c = 0; c < 24; ++c) J.col(c) = ((f(c, h) - f(c, -h)) / (2 * h)).template cast<double>();
  return J;
}

template <class A, class B>
double relative(const A& a, const B& b) {
  return (a - b).norm() / b.norm();
}

class MortarTopology : public ::testing::TestWithParam<Multipliers> {};
INSTANTIATE_TEST_SUITE_P(Kinds, MortarTopology, ::testing::Values(Multipliers::standard, Multipliers::dual));

// ±1e-12 (issue 24 §6) lies inside the ON band of (4.70) (1e-9 × the slave's size), where both signs see the
// same side; ±1e-8 lies outside it, where the two sides differ.
constexpr double deltas[] = {1e-12, 1e-8};

// (4.80): ∂g̃/∂x at δ = ±1e-12 and ±1e-8 against central differences that stay on δ's side (h = |δ|/10); at
// δ = 0 equal to one of the two sides (the overlap of a configuration at most tol away, (4.70)).
TEST_P(MortarTopology, GapGradientMatchesDifferencesOnEachSideOfTheChange) {
  const Multipliers kind = GetParam();
  for (const Configuration& c : configurations)
    for (double angle : {0.0, 0.3})
      for (double delta : deltas) {
        SCOPED_TRACE(std::string(c.name) + (angle == 0 ? "" : ", turned") +
                     ", |δ| = " + std::to_string(delta));
        Jacobian side[2];
        for (int k = 0; k < 2; ++k) {
          SegmentNodes s, m;
          faces(c, k == 0 ? -delta : delta, angle, s, m);
          side[k] = pair_gaps(s, m, kind).gradient;
          const double error = relative(side[k], differences(4, delta / 10, [&](int col, Long h) {
                                          return long_gaps(s, m, kind, col, h);
                                        }));
          std::printf("%s%s, δ = %+.0e: |∂g̃ − central| / |∂g̃| = %.1e\n", c.name,
                      angle == 0 ? "" : " (turned)", k == 0 ? -delta : delta, error);
          EXPECT_LT(error, 1e-6);
        }
        SegmentNodes s, m;
        faces(c, 0, angle, s, m);
        const Jacobian at = pair_gaps(s, m, kind).gradient;
        // the side's own variation over δ: O(δ)
        EXPECT_LT(std::min(relative(at, side[0]), relative(at, side[1])), 1e-9 + 100 * delta);
      }
}

// (4.81): Σ λ_j ∂²g̃_j/∂x² at δ = ±1e-12 and ±1e-8 against central differences of λ·∂g̃/∂x on δ's side (the
// overlap is C¹ but not C² where a vertex crosses an edge: the second derivatives of the two sides differ).
TEST_P(MortarTopology, WeightedHessianMatchesDifferencesOnEachSideOfTheChange) {
  const Multipliers kind = GetParam();
  const Eigen::Vector4d lambda(-1, -0.7, -1.3, -0.9);
  for (const Configuration& c : configurations)
    for (double d : {-deltas[0], deltas[0], -deltas[1], deltas[1]}) {
      SCOPED_TRACE(std::string(c.name) + ", δ = " + std::to_string(d));
      SegmentNodes s, m;
      faces(c, d, 0.3, s, m);
      Matrix24 H;
      pair_gaps(s, m, kind, lambda, H);
      const double error = relative(H, differences(24, std::abs(d) / 10, [&](int col, Long h) {
                                      return long_force(s, m, kind, lambda, col, h);
                                    }));
      std::printf("%s, δ = %+.0e: |H − central| / |H| = %.1e\n", c.name, d, error);
      EXPECT_LT(error, 1e-5);  // the differences' round-off: 1e-6–2e-6 measured
    }
}

}  // namespace
}  // namespace stoss::contact::mortar
