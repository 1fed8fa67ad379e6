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
/// Extended precision (the tests' finite differences) decides in double.
inline double value_of(long double x) {
  return static_cast<double>(x);
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

/// |a − b| of the values, from the values (no dual-number difference) and without glibc's hypot (8 % of the
/// seed example with mortar).
template <class T>
double distance_value(const Point2<T>& a, const Point2<T>& b) {
  const double dx = value_of(a[0]) - value_of(b[0]), dy = value_of(a[1]) - value_of(b[1]);
  return std::sqrt(dx * dx + dy * dy);
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

/// A line of the clipping: the supporting line of an edge of one of the input polygons, through its two
/// input vertices (so that an intersection is computed from the inputs, not from earlier intersections).
template <class T>
struct ClipLine {
  Point2<T> a, b;
};

/// A vertex of the polygon being clipped and the line its outgoing edge lies on (index into the lines).
template <class T>
struct ClipVertex {
  Point2<T> p;
  int line = -1;
};

/// Where a vertex is against the clip line (4.70): strictly inside or outside, or within the tolerance of it.
enum class Side { in, on, out };

/// One Sutherland–Hodgman pass (4.70): keeps the part of `subject` left of the line `lines[k]`. A vertex
/// within `tol` of the line is ON it: it is never intersected; a run of ON vertices between an inside and an
/// outside neighbour is either dropped for the crossing of its edge to the outside neighbour or kept with
/// the crossing of its edge to the inside neighbour (dropped unless that edge crosses 4× more steeply). Each
/// vertex stays the intersection of the lines of its two edges, so the polygon is the overlap of a
/// configuration at most `tol` away and dual numbers differentiate that overlap; no intersection of nearly
/// parallel lines is formed.
template <class T>
std::vector<ClipVertex<T>> clip_by_line(const std::vector<ClipVertex<T>>& subject,
                                        const std::vector<ClipLine<T>>& lines, int k, double tol) {
  const ClipLine<T>& clip = lines[k];
  const Point2<T> edge = clip.b - clip.a;
  const T length = edge.norm();
  const Point2<T> inward(-edge[1] / length, edge[0] / length);
  const auto distance = [&](const Point2<T>& x) { return T((x - clip.a).dot(inward)); };  // (4.70)
  const size_t n = subject.size();
  std::vector<double> s(n);
  std::vector<Side> side(n);
  size_t start = n;
  bool any_out = false;
  for (size_t i = 0; i < n; ++i) {
    s[i] = value_of(distance(subject[i].p));
    side[i] = s[i] > tol ? Side::in : s[i] < -tol ? Side::out : Side::on;
    if (side[i] == Side::in && start == n) start = i;
    any_out = any_out || side[i] == Side::out;
  }
  // A kept ON vertex stays where it is, also up to tol outside: moved onto the line (in value only) it would
  // no longer be the point whose derivative the dual numbers carry.
  if (!any_out) return subject;  // nothing outside: every vertex stays
  if (start == n) return {};     // nothing strictly inside: at most a sliver of width tol
  // The crossing of the edge i → i+1 with the clip line (4.70), from the input points of the edge's line; the
  // edge's own ends (clamped) where round-off would put it off the edge.
  const auto crossing = [&](size_t i) -> Point2<T> {
    const size_t j = (i + 1) % n;
    const ClipLine<T>& l = lines[subject[i].line];
    const T s0 = distance(l.a), s1 = distance(l.b);
    if (value_of(T(s0 - s1)) != 0) {
      const Point2<T> x = l.a + (l.b - l.a) * T(s0 / (s0 - s1));
      const Point2<double> xv(value_of(x[0]), value_of(x[1]));
      const Point2<double> pi(value_of(subject[i].p[0]), value_of(subject[i].p[1]));
      const Point2<double> d(value_of(subject[j].p[0]) - pi[0], value_of(subject[j].p[1]) - pi[1]);
      const double u = d.squaredNorm() > 0 ? (xv - pi).dot(d) / d.squaredNorm() : 0;
      if (std::isfinite(u) && (xv - pi - u * d).norm() <= 2 * tol && u * d.norm() >= -2 * tol &&
          (u - 1) * d.norm() <= 2 * tol)
        return x;
    }
    if (!(std::abs(s[i] - s[j]) > 0)) return subject[i].p;
    const double t = s[i] / (s[i] - s[j]);
    if (t <= 0) return subject[i].p;
    if (t >= 1) return subject[j].p;
    const T si = distance(subject[i].p), sj = distance(subject[j].p);
    return subject[i].p + (subject[j].p - subject[i].p) * T(si / (si - sj));
  };
  // How steeply the edge i → i+1 crosses the line (sine of the angle); −1 if the crossing lies off the edge.
  const auto steepness = [&](size_t i) {
    const size_t j = (i + 1) % n;
    const double length_ij = distance_value<T>(subject[i].p, subject[j].p);
    if (!(length_ij > 0)) return -1.0;
    const double t = s[i] / (s[i] - s[j]);
    if (!std::isfinite(t) || -t * length_ij > 2 * tol || (t - 1) * length_ij > 2 * tol) return -1.0;
    return std::abs(s[i] - s[j]) / length_ij;
  };
  // Drop the run (cross the edge beside it that stays outside) unless that edge crosses far less steeply.
  const auto drop_run = [](double dropping, double keeping) {
    return dropping >= 0 && dropping >= 0.25 * keeping;
  };
  std::vector<ClipVertex<T>> out;
  for (size_t step = 0; step < n;) {
    const size_t i = (start + step) % n, j = (i + 1) % n;
    if (side[i] != Side::on) {
      if (side[i] == Side::in) out.push_back(subject[i]);
      if (side[i] == Side::in && side[j] == Side::out) out.push_back({crossing(i), k});  // leaves along k
      if (side[i] == Side::out && side[j] == Side::in) out.push_back({crossing(i), subject[i].line});
      ++step;
      continue;
    }
    size_t run = 0;  // the ON run i … last, between prev and next (start is inside, so no wrap past it)
    while (side[(i + run) % n] == Side::on) ++run;
    const size_t prev = (i + n - 1) % n, last = (i + run - 1) % n;
    const Side before = side[prev], after = side[(last + 1) % n];
    if (before == Side::in && after == Side::out) {
      if (drop_run(steepness(prev), steepness(last))) {
        out.push_back({crossing(prev), k});
      } else {
        for (size_t r = 0; r < run; ++r) out.push_back(subject[(i + r) % n]);
        out.push_back({crossing(last), k});
      }
    } else if (before == Side::out && after == Side::in) {
      if (drop_run(steepness(last), steepness(prev))) {
        out.push_back({crossing(last), subject[last].line});
      } else {
        out.push_back({crossing(prev), subject[prev].line});
        for (size_t r = 0; r < run; ++r) out.push_back(subject[(i + r) % n]);
      }
    } else if (before == Side::in) {
      for (size_t r = 0; r < run; ++r) out.push_back(subject[(i + r) % n]);
    }
    step += run;
  }
  return out;
}

/// The overlap of `subject` (any orientation made counter-clockwise by the caller) with the convex,
/// counter-clockwise `clip` polygon (4.70). Empty when fewer than 3 distinct vertices remain or the area
/// is not above `tol`². Coincident vertices of the overlap are kept (a zero-length edge between them): each
/// vertex is the intersection of its edges' lines, which is what makes the derivatives right (4.70).
template <class T>
Polygon<T> clip_convex(const Polygon<T>& subject, const Polygon<T>& clip, double tol) {
  const Polygon<T> p = without_duplicates(subject, tol), c = without_duplicates(clip, tol);
  if (c.size() < 3 || p.size() < 3) return {};
  std::vector<ClipLine<T>> lines;
  std::vector<ClipVertex<T>> out;
  for (size_t i = 0; i < p.size(); ++i)
    lines.push_back({p[i], p[(i + 1) % p.size()]}), out.push_back({p[i], int(i)});
  for (size_t k = 0; k < c.size(); ++k) lines.push_back({c[k], c[(k + 1) % c.size()]});
  for (size_t k = 0; k < c.size() && out.size() >= 3; ++k)
    out = clip_by_line(out, lines, static_cast<int>(p.size() + k), tol);
  Polygon<T> polygon;
  for (const ClipVertex<T>& v : out) polygon.push_back(v.p);
  if (without_duplicates(polygon, tol).size() < 3 || !(value_of(signed_area(polygon)) > tol * tol)) return {};
  return polygon;
}

/// A triangle of a mortar segment (4.72), counter-clockwise.
template <class T>
struct Triangle {
  Point2<T> a, b, c;
};

/// The fan about the area centroid (4.72): triangles (c, v_i, v_{i+1}), every one, also those of zero area at
/// a zero-length edge (its area's derivative is not zero). `min_area`: below it the centroid is the mean.
template <class T>
std::vector<Triangle<T>> fan_triangles(const Polygon<T>& p, double min_area) {
  std::vector<Triangle<T>> out;
  if (p.size() < 3) return out;
  const Point2<T> c = centroid(p, min_area);
  for (size_t i = 0; i < p.size(); ++i) out.push_back({c, p[i], p[(i + 1) % p.size()]});
  return out;
}

}  // namespace stoss::contact::mortar
