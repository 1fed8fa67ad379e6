#pragma once
/// @file Convex polygon clipping in a mortar plane (docs/theory.md §4.7, (4.70)–(4.72)): Sutherland–Hodgman
/// against a convex clip polygon, no convex-hull step, and the fan triangulation about the centroid.
/// Templated on the scalar so that forward-mode dual numbers (dual_number.hpp) pass through.

#include <Eigen/Core>
#include <cmath>
#include <vector>

namespace stoss::contact::mortar {

template <class T>
using Point2 = Eigen::Matrix<T, 2, 1>;
template <class T>
using Polygon = std::vector<Point2<T>>;

/// The value of a scalar (double or a dual number).
inline double value_of(double x) {
  return x;
}
/// Nested dual numbers (second derivatives, mortar_pair_derivatives.hpp) unwrap to the innermost value.
template <class T>
double value_of(const T& x) {
  return value_of(x.value());
}

template <class T>
T cross2(const Point2<T>& a, const Point2<T>& b) {
  return a[0] * b[1] - a[1] * b[0];
}

/// Signed area by the shoelace formula (4.71): positive for counter-clockwise vertices.
template <class T>
T signed_area(const Polygon<T>& p) {
  T twice(0.0);
  for (size_t i = 0; i < p.size(); ++i) twice += cross2<T>(p[i], p[(i + 1) % p.size()]);
  return T(0.5) * twice;
}

/// Centroid of the polygon's area (4.71); the vertex mean if the area is below `min_area`. The area
/// centroid does not move when a vertex is duplicated, so the fan (4.72) does not jump at a topology change.
template <class T>
Point2<T> centroid(const Polygon<T>& p, double min_area) {
  Point2<T> c(T(0.0), T(0.0));
  const T area = signed_area(p);
  if (!(std::abs(value_of(area)) > min_area)) {
    for (const Point2<T>& v : p) c += v;
    return c / T(double(p.size()));
  }
  for (size_t i = 0; i < p.size(); ++i) {
    const Point2<T>& a = p[i];
    const Point2<T>& b = p[(i + 1) % p.size()];
    c += (a + b) * cross2<T>(a, b);
  }
  return c / (T(6.0) * area);
}

/// |a − b| of the values.
template <class T>
double distance_value(const Point2<T>& a, const Point2<T>& b) {
  return std::hypot(value_of(T(a[0] - b[0])), value_of(T(a[1] - b[1])));
}

/// Removes consecutive vertices closer than `tol` (and a last one equal to the first).
template <class T>
Polygon<T> without_duplicates(const Polygon<T>& p, double tol) {
  Polygon<T> out;
  for (const Point2<T>& v : p)
    if (out.empty() || distance_value<T>(v, out.back()) > tol) out.push_back(v);
  while (out.size() > 1 && distance_value<T>(out.front(), out.back()) <= tol) out.pop_back();
  return out;
}

/// One Sutherland–Hodgman pass (4.70): keeps the part of `subject` left of the directed line a → b. A
/// vertex less than `tol` outside the line is moved onto it (inwards, so the result never grows); an
/// intersection is made only where an edge goes from strictly inside to strictly outside or back, so no
/// near-duplicate appears.
template <class T>
Polygon<T> clip_by_line(const Polygon<T>& subject, const Point2<T>& a, const Point2<T>& b, double tol) {
  const Point2<T> edge = b - a;
  const T length = edge.norm();
  const Point2<T> inward(-edge[1] / length, edge[0] / length);
  std::vector<T> s(subject.size());
  Polygon<T> snapped = subject;
  for (size_t i = 0; i < subject.size(); ++i) {
    s[i] = (subject[i] - a).dot(inward);  // (4.70) signed distance
    if (value_of(s[i]) < 0 && value_of(s[i]) >= -tol) snapped[i] -= s[i] * inward, s[i] = T(0.0);
  }
  Polygon<T> out;
  for (size_t i = 0; i < subject.size(); ++i) {
    const size_t j = (i + 1) % subject.size();
    const double si = value_of(s[i]), sj = value_of(s[j]);
    if (si >= 0) out.push_back(snapped[i]);
    if ((si > 0 && sj < 0) || (si < 0 && sj > 0)) {
      const T t = s[i] / (s[i] - s[j]);  // (4.70)
      out.push_back(snapped[i] + t * (snapped[j] - snapped[i]));
    }
  }
  return out;
}

/// The overlap of `subject` (any orientation made counter-clockwise by the caller) with the convex,
/// counter-clockwise `clip` polygon (4.70). Empty when fewer than 3 distinct vertices remain or the area
/// is not above `tol`².
template <class T>
Polygon<T> clip_convex(const Polygon<T>& subject, const Polygon<T>& clip, double tol) {
  Polygon<T> out = without_duplicates(subject, tol);
  const Polygon<T> c = without_duplicates(clip, tol);
  if (c.size() < 3) return {};
  for (size_t k = 0; k < c.size() && out.size() >= 3; ++k)
    out = without_duplicates(clip_by_line(out, c[k], c[(k + 1) % c.size()], tol), tol);
  if (out.size() < 3 || !(value_of(signed_area(out)) > tol * tol)) return {};
  return out;
}

/// A triangle of a mortar segment (4.72), counter-clockwise.
template <class T>
struct Triangle {
  Point2<T> a, b, c;
};

/// The fan about the area centroid (4.72): triangles (c, v_i, v_{i+1}); those of area ≤ `min_area` dropped.
template <class T>
std::vector<Triangle<T>> fan_triangles(const Polygon<T>& p, double min_area) {
  std::vector<Triangle<T>> out;
  if (p.size() < 3) return out;
  const Point2<T> c = centroid(p, min_area);
  for (size_t i = 0; i < p.size(); ++i) {
    Triangle<T> t{c, p[i], p[(i + 1) % p.size()]};
    if (value_of(cross2<T>(t.b - t.a, t.c - t.a)) > 2 * min_area) out.push_back(t);
  }
  return out;
}

}  // namespace stoss::contact::mortar
