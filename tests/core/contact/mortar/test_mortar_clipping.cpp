#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/contact/mortar/polygon.hpp"

namespace stoss::contact::mortar {
namespace {
using P = Point2<double>;
using Poly = Polygon<double>;
constexpr double tol = 1e-14;

Poly square(double x0, double y0, double x1, double y1) {
  return {P(x0, y0), P(x1, y0), P(x1, y1), P(x0, y1)};
}

Poly rotated(const Poly& p, double angle) {
  Poly out;
  for (const P& v : p)
    out.emplace_back(std::cos(angle) * v[0] - std::sin(angle) * v[1],
                     std::sin(angle) * v[0] + std::cos(angle) * v[1]);
  return out;
}

double clipped_area(const Poly& subject, const Poly& clip) {
  const Poly c = clip_convex(subject, clip, tol);
  return c.empty() ? 0.0 : signed_area(c);
}

// The clip polygon is never larger than either input (issue 24 §6), beyond round-off of the shoelace sum and
// beyond `slack`: ON vertices (within tol of a clip line, (4.70)) stay where they are, so an input up to tol
// outside the other adds a sliver of width ≤ tol.
void expect_not_larger(const Poly& a, const Poly& b, double slack = 1e-15) {
  const double area = clipped_area(a, b);
  EXPECT_LE(area, std::min(std::abs(signed_area(a)), std::abs(signed_area(b))) + slack);
  EXPECT_GE(area, 0.0);
}

TEST(MortarClipping, CoincidentQuadsGiveTheQuad) {
  const Poly q = square(0, 0, 1, 1);
  const Poly c = clip_convex(q, q, tol);
  ASSERT_EQ(c.size(), 4u);
  EXPECT_NEAR(signed_area(c), 1.0, 1e-15);
  for (const P& v : q)
    EXPECT_TRUE(std::any_of(c.begin(), c.end(), [&](const P& w) { return (w - v).norm() < 1e-15; }));
}

TEST(MortarClipping, DisjointQuadsGiveNothing) {
  EXPECT_TRUE(clip_convex(square(2, 0, 3, 1), square(0, 0, 1, 1), tol).empty());
  EXPECT_TRUE(clip_convex(square(1 + 1e-9, 0, 2, 1), square(0, 0, 1, 1), tol).empty());
}

TEST(MortarClipping, OneInsideTheOtherGivesTheInner) {
  const Poly inner = square(0.2, 0.3, 0.7, 0.6), outer = square(0, 0, 1, 1);
  EXPECT_NEAR(clipped_area(inner, outer), 0.15, 1e-15);
  EXPECT_NEAR(clipped_area(outer, inner), 0.15, 1e-15);
}

TEST(MortarClipping, DegenerateCasesStayWithinTheExactArea) {
  const Poly unit = square(0, 0, 1, 1);
  struct Case {
    const char* name;
    Poly subject;
    double exact;
  };
  const Case cases[] = {
      {"sliver of area 1e-14", square(1 - 1e-14, 0, 2, 1), 1e-14},
      {"sliver quad of area 1e-14", square(0.2, 0.3, 0.7, 0.3 + 2e-14), 1e-14},
      {"collinear points (a triangle with a vertex mid-edge)",
       {P(0.5, 0.5), P(1.5, 0.5), P(2.5, 0.5), P(1.5, 1.5)},
       0.125},
      {"all four points collinear", {P(-1, 0.5), P(0, 0.5), P(1, 0.5), P(2, 0.5)}, 0},
      {"a vertex on an edge", {P(0.5, 0.5), P(1, 0.2), P(1.5, 0.5), P(1, 0.8)}, 0.15},
      {"coincident vertices", {P(0.5, 0.5), P(2, 0.5), P(2, 0.5), P(0.5, 2)}, 0.25},
      {"parallel edges on the clip edges", square(0.5, 0, 1.5, 1), 0.5},
      {"parallel edges 1e-15 apart", square(1e-15, 1e-15, 1 - 1e-15, 1 + 1e-15), 1 - 3e-15},
      {"a coincident corner", square(1, 1, 2, 2), 0},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    EXPECT_NEAR(clipped_area(c.subject, unit), c.exact, 1e-12);
    expect_not_larger(c.subject, unit);
  }
}

// A subject 5e-15 larger than the clip on every side: all its vertices are ON (4.70) and stay, so the overlap
// is the subject, larger than the clip by its sliver 4 × 5e-15, within tol × the perimeter.
TEST(MortarClipping, OnVerticesOutsideByLessThanTheToleranceStay) {
  const Poly unit = square(0, 0, 1, 1), larger = square(-5e-15, -5e-15, 1 + 5e-15, 1 + 5e-15);
  const Poly c = clip_convex(larger, unit, tol);
  ASSERT_EQ(c.size(), 4u);
  EXPECT_NEAR(signed_area(c), signed_area(larger), 1e-16);
  expect_not_larger(larger, unit, 4 * tol);
}

// Concentric squares of half-width 1, one turned by θ = 30° about z: each corner of the fixed square is cut
// by one edge of the turned one, a right triangle with legs 1 − tan(θ/2) and 1 − (1 − sin θ)/cos θ.
TEST(MortarClipping, RotatedQuadsGiveTheExactOverlap) {
  const double theta = M_PI / 6;
  const double legs = (1 - std::tan(theta / 2)) * (1 - (1 - std::sin(theta)) / std::cos(theta));
  const double exact = 4 - 2 * legs;
  const Poly fixed = square(-1, -1, 1, 1), turned = rotated(fixed, theta);
  EXPECT_NEAR(clipped_area(turned, fixed), exact, 1e-14);
  EXPECT_NEAR(clipped_area(fixed, turned), exact, 1e-14);
  EXPECT_EQ(clip_convex(turned, fixed, tol).size(), 8u);
  expect_not_larger(turned, fixed);
}

TEST(MortarClipping, FanAboutTheCentroidCoversThePolygon) {
  const Poly p = clip_convex(rotated(square(-1, -1, 1, 1), 0.4), square(-0.8, -1.1, 1.2, 0.9), tol);
  double sum = 0;
  for (const Triangle<double>& t : fan_triangles(p, 1e-28)) {
    const double area = 0.5 * cross2<double>(t.b - t.a, t.c - t.a);
    EXPECT_GT(area, 0);
    sum += area;
  }
  EXPECT_NEAR(sum, signed_area(p), 1e-15);
}

}  // namespace
}  // namespace stoss::contact::mortar
