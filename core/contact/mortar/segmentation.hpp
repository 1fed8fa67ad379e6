#pragma once
/// @file One slave face against one master face in the slave's mortar plane (docs/theory.md §4.7,
/// (4.73)–(4.75)): the plane, the projected quads, their clip polygon, the triangle rule and the inverse
/// bilinear map of a plane point onto each quad.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <stdexcept>
#include <unsupported/Eigen/AutoDiff>

#include "core/contact/mortar/polygon.hpp"

namespace stoss::contact::mortar {

template <class T>
using Vec3 = Eigen::Matrix<T, 3, 1>;
template <class T>
using QuadNodes = std::array<Vec3<T>, 4>;  ///< corners in the face order of docs/theory.md §1.1

/// The slave face's mortar plane (4.73): centre x0, unit normal n (out of the slave body), e1 × e2 = n.
template <class T>
struct MortarPlane {
  Vec3<T> x0, n, e1, e2;
  Point2<T> coordinates(const Vec3<T>& x) const { return {(x - x0).dot(e1), (x - x0).dot(e2)}; }
  T height(const Vec3<T>& x) const { return (x - x0).dot(n); }
};

template <class T>
MortarPlane<T> mortar_plane(const QuadNodes<T>& s) {
  MortarPlane<T> p;
  p.x0 = (s[0] + s[1] + s[2] + s[3]) * T(0.25);
  const Vec3<T> normal = (s[2] - s[0]).cross(s[3] - s[1]);  // (4.73) ∝ τ_1(0) × τ_2(0)
  p.n = normal / normal.norm();
  const Vec3<T> tau1 = (s[1] + s[2] - s[0] - s[3]) * T(0.25);
  const Vec3<T> in_plane = tau1 - p.n * tau1.dot(p.n);
  p.e1 = in_plane / in_plane.norm();
  p.e2 = p.n.cross(p.e1);
  return p;
}

template <class T>
Polygon<T> projected(const MortarPlane<T>& plane, const QuadNodes<T>& q) {
  Polygon<T> out;
  for (const Vec3<T>& x : q) out.push_back(plane.coordinates(x));
  return out;
}

/// Bilinear shape functions (3.1) at ξ.
template <class T>
Eigen::Matrix<T, 4, 1> shape(const Point2<T>& xi) {
  Eigen::Matrix<T, 4, 1> N;
  N << T(0.25) * (T(1.0) - xi[0]) * (T(1.0) - xi[1]), T(0.25) * (T(1.0) + xi[0]) * (T(1.0) - xi[1]),
      T(0.25) * (T(1.0) + xi[0]) * (T(1.0) + xi[1]), T(0.25) * (T(1.0) - xi[0]) * (T(1.0) + xi[1]);
  return N;
}

/// One Newton step of (4.75) for ξ: J(ξ)⁻¹ (Σ N_K(ξ) q_K − p).
template <class T>
Point2<T> bilinear_newton_step(const Polygon<T>& q, const Point2<T>& p, const Point2<T>& xi) {
  const T a = T(1.0) - xi[0], b = T(1.0) + xi[0], c = T(1.0) - xi[1], d = T(1.0) + xi[1];
  const Point2<T> r = (q[0] * (a * c) + q[1] * (b * c) + q[2] * (b * d) + q[3] * (a * d)) * T(0.25) - p;
  const Point2<T> j1 = ((q[1] - q[0]) * c + (q[2] - q[3]) * d) * T(0.25);
  const Point2<T> j2 = ((q[3] - q[0]) * a + (q[2] - q[1]) * b) * T(0.25);
  const T det = cross2<T>(j1, j2);
  return Point2<T>((j2[1] * r[0] - j2[0] * r[1]) / det, (j1[0] * r[1] - j1[1] * r[0]) / det);
}

/// The values of a point of dual numbers.
template <class T>
Point2<double> point_value(const Point2<T>& x) {
  return {value_of(x[0]), value_of(x[1])};
}

/// How many Newton steps on the dual numbers make a converged ξ's derivatives exact: each step from a
/// converged value doubles the order of the error in the perturbation, so one for first derivatives, two for
/// second ones. Unknown scalars get two.
template <class T>
struct DerivativeOrder {
  static constexpr int value = 2;
};
template <>
struct DerivativeOrder<double> {
  static constexpr int value = 0;
};
template <>
struct DerivativeOrder<long double> {  // the tests' extended precision: one step past double's round-off
  static constexpr int value = 1;
};
template <class D>
struct DerivativeOrder<Eigen::AutoDiffScalar<D>> {
  static constexpr int value = 1 + DerivativeOrder<typename D::Scalar>::value;
};

/// ξ with Σ N_K(ξ) q_K = p for the projected quad q (4.75), by Newton from ξ = 0 on the values until
/// |Δξ| < 1e-14, then DerivativeOrder<T> more steps on the dual numbers from that ξ, which makes their first
/// (and second) derivatives exact (the derivatives of the solution do not depend on the path to it). Throws
/// std::runtime_error if 30 iterations do not converge (a projected quad folded over itself).
template <class T>
Point2<T> inverse_bilinear(const Polygon<T>& q, const Point2<T>& p) {
  const auto small = [](const auto& step) {  // |Δξ| < 1e-14, without hypot (8 % of a mortar run)
    return value_of(step[0]) * value_of(step[0]) + value_of(step[1]) * value_of(step[1]) < 1e-28;
  };
  Polygon<double> q_value;
  for (const Point2<T>& v : q) q_value.push_back(point_value(v));
  const Point2<double> p_value = point_value(p);
  Point2<double> xi_value(0.0, 0.0);
  for (int iteration = 0;; ++iteration) {
    if (iteration == 30)
      throw std::runtime_error("mortar: the inverse bilinear map (docs/theory.md (4.75)) did not converge");
    const Point2<double> step = bilinear_newton_step(q_value, p_value, xi_value);
    xi_value -= step;
    if (small(step)) break;
  }
  Point2<T> xi = Point2<T>(T(xi_value[0]), T(xi_value[1]));
  for (int k = 0; k < DerivativeOrder<T>::value; ++k) xi -= bilinear_newton_step(q, p, xi);
  return xi;
}

/// A 7-point rule on a triangle, exact for polynomials of degree 5 (Radon 1948; (4.74)): barycentric
/// points and weights that sum to 1 (multiply by the triangle's area).
struct TrianglePoint {
  double l1, l2, l3, weight;
};
const std::array<TrianglePoint, 7>& triangle_rule();

}  // namespace stoss::contact::mortar
