#pragma once
/// @file Mortar integrals of one slave face against one master face (docs/theory.md §4.7, (4.77)–(4.80)):
/// D (slave × slave), M (slave × master) and the weighted gaps g̃_j, with standard or dual multipliers.

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <unsupported/Eigen/AutoDiff>

#include "core/contact/mortar/segmentation.hpp"
#include "core/contact/types.hpp"

namespace stoss::contact::mortar {

/// Φ_j = N_j (standard) or Φ_j = Σ_k a_jk N_k with ∫Φ_j N_k = δ_jk ∫N_j on the slave face (dual, (4.77)).
enum class Multipliers { standard, dual };

template <class T>
struct FacePairIntegrals {
  Eigen::Matrix<T, 4, 4> D = Eigen::Matrix<T, 4, 4>::Zero();    ///< D_jk = ∫ Φ_j N_k (4.78)
  Eigen::Matrix<T, 4, 4> M = Eigen::Matrix<T, 4, 4>::Zero();    ///< M_jl = ∫ Φ_j N^m_l (4.78)
  Eigen::Matrix<T, 4, 1> gap = Eigen::Matrix<T, 4, 1>::Zero();  ///< g̃_j (4.79)
  T area = T(0.0);                                              ///< the clip polygon's area
  double facing_weight = 0;                                     ///< ψ of (4.76) (0: not paired)
  Eigen::Vector4d weight = Eigen::Vector4d::Zero();             ///< the values of D_jj
  Eigen::Vector4d basis_integral =
      Eigen::Vector4d::Zero();  ///< the values of ∫ Φ_j ψ dA over the clip polygon
  int triangles = 0;
};

/// What face_pair_integrals computes: D, M and the gaps, or the gaps and D_jj's values only (the derivatives
/// (4.80), (4.81) need no more: D and M in dual numbers were a third of their cost).
enum class Integrals { all, gaps };

/// Dual coefficients a = D_e M_e^{-1} (4.77) over the whole slave face in the plane's measure; 2 × 2
/// Gauss points are exact (N_j N_k det ∂p/∂ξ has degree 3 in each ξ^α).
template <class T>
Eigen::Matrix<T, 4, 4> dual_coefficients(const Polygon<T>& slave) {
  Eigen::Matrix<T, 4, 4> Me = Eigen::Matrix<T, 4, 4>::Zero(), De = Me;
  const double g = 1 / std::sqrt(3.0);
  for (double u : {-g, g})
    for (double v : {-g, g}) {
      const Point2<T> xi{T(u), T(v)};
      const Eigen::Matrix<T, 4, 1> N = shape(xi);
      const Point2<T> j1 = ((slave[1] - slave[0]) * T(1 - v) + (slave[2] - slave[3]) * T(1 + v)) * T(0.25);
      const Point2<T> j2 = ((slave[3] - slave[0]) * T(1 - u) + (slave[2] - slave[1]) * T(1 + u)) * T(0.25);
      const T J = cross2<T>(j1, j2);
      Me += N * N.transpose() * J;
      for (int k = 0; k < 4; ++k) De(k, k) += N[k] * J;
    }
  return De * Me.inverse();  // (4.77)
}

/// A master face faces the slave face when n_s · n̂_m < −facing_cosine (4.76): seen at less than 60° from
/// the slave's normal, its projection keeps at least half of its area. Nearly edge-on faces (a box slave's
/// side against the master it rests on) project onto slivers that fold over and stall the inverse map (4.75).
/// The pair's measure fades out towards the cut (fade_start, facing_fade), so that the cut is no jump in g̃_j:
/// as a jump it fell among the two-balls example's active pairs, and Newton wandered there for 25 iterations
/// in a fifth of the steps (at 75.5° or 66° it stalled outright).
inline constexpr double facing_cosine = 0.5;
/// Where the fade starts: faces seen within 30° of the slave's normal count in full.
inline constexpr double fade_start = 0.8660254037844386;  // cos 30°

/// ψ of (4.76): 1 from 30° on the slave's normal, 0 at the 60° cut, the C1 cubic 3s² − 2s³ in the facing
/// cosine between.
template <class T>
T facing_fade(const T& facing) {
  const T s = (facing - T(facing_cosine)) / T(fade_start - facing_cosine);
  return value_of(s) >= 1 ? T(1.0) : s * s * (T(3.0) - T(2.0) * s);
}

/// The integrals over the clip polygon of the slave face s and the master face m (4.77)–(4.80), in the
/// measure ψ dA of (4.76). Zero when the faces do not face each other (4.76) or do not overlap in the slave's
/// plane. The gap is g = (x_m − x_s)·n_s = (x_s − x_m)·n with n = −n_s from the master to the slave (§0).
/// `offset`: per slave node j a constant c_j taken off the gap, g̃_j = ∫ Φ_j (g − c_j) (the frozen nodal gap
/// of persist and located, (4.83)).
template <class T>
FacePairIntegrals<T> face_pair_integrals(const QuadNodes<T>& s, const QuadNodes<T>& m, Multipliers kind,
                                         Integrals what = Integrals::all,
                                         const Eigen::Vector4d& offset = Eigen::Vector4d::Zero()) {
  FacePairIntegrals<T> out;
  const MortarPlane<T> plane = mortar_plane(s);
  const Vec3<T> master_normal = (m[2] - m[0]).cross(m[3] - m[1]);
  const T facing = -T(master_normal.dot(plane.n)) / T(master_normal.norm());
  if (!(value_of(facing) > facing_cosine)) return out;  // (4.76)
  const T fade = facing_fade(facing);                   // ψ (4.76)
  out.facing_weight = value_of(fade);
  const Polygon<T> ps = projected(plane, s), pm = projected(plane, m);
  Polygon<T> pm_ccw = pm;
  if (value_of(signed_area(pm)) < 0) std::reverse(pm_ccw.begin(), pm_ccw.end());
  double size = 0;
  for (int k = 0; k < 4; ++k) size = std::max(size, distance_value<T>(ps[k], ps[(k + 1) % 4]));
  // (4.70): the ON band. Newton iterates of a flat patch move a slave rim edge lying on a master rim edge to
  // either side of the kink there; inside the band they all see one side (1e-14: Newton stalls at 1e-7).
  const double tol = 1e-9 * size;
  for (int k = 0; k < 4; ++k)  // (4.70) needs a convex clip polygon
    if (value_of(cross2<T>(ps[(k + 1) % 4] - ps[k], ps[(k + 2) % 4] - ps[(k + 1) % 4])) < -tol * tol)
      throw std::domain_error(
          "mortar: the slave face's projection onto its plane is not convex (docs/theory.md §4.7)");
  const Polygon<T> clip = clip_convex(pm_ccw, ps, tol);
  if (clip.empty()) return out;
  const Eigen::Matrix<T, 4, 4> a = kind == Multipliers::dual
                                       ? dual_coefficients(ps)
                                       : Eigen::Matrix<T, 4, 4>(Eigen::Matrix<T, 4, 4>::Identity());
  for (const Triangle<T>& t : fan_triangles(clip, tol * tol)) {
    const T area = T(0.5) * cross2<T>(t.b - t.a, t.c - t.a);
    out.area += area;
    ++out.triangles;
    for (const TrianglePoint& q : triangle_rule()) {
      const Point2<T> p = t.a * T(q.l1) + t.b * T(q.l2) + t.c * T(q.l3);
      const Eigen::Matrix<T, 4, 1> Ns = shape(inverse_bilinear(ps, p)), Nm = shape(inverse_bilinear(pm, p));
      const Eigen::Matrix<T, 4, 1> Phi = a * Ns;
      Vec3<T> xs = Vec3<T>::Zero(), xm = Vec3<T>::Zero();
      for (int K = 0; K < 4; ++K) xs += s[K] * Ns[K], xm += m[K] * Nm[K];
      const T w = area * T(q.weight) * fade;  // (4.74) in the measure ψ dA (4.76)
      if (what == Integrals::all) {
        out.D += Phi * Ns.transpose() * w;  // (4.78)
        out.M += Phi * Nm.transpose() * w;  // (4.78)
      } else {
        for (int j = 0; j < 4; ++j)
          out.weight[j] += value_of(Phi[j]) * value_of(Ns[j]) * value_of(w);  // (4.78)
      }
      const T gap_w = T((xm - xs).dot(plane.n)) * w;
      for (int j = 0; j < 4; ++j) {
        out.gap[j] += Phi[j] * (offset[j] == 0 ? gap_w : T(gap_w - w * offset[j]));  // (4.79), (4.83)
        out.basis_integral[j] += value_of(Phi[j]) * value_of(w);
      }
    }
  }
  if (what == Integrals::all)
    for (int j = 0; j < 4; ++j) out.weight[j] = value_of(out.D(j, j));
  return out;
}

/// The face nodes as QuadNodes (rows of SegmentNodes).
QuadNodes<double> quad_nodes(const SegmentNodes& rows);

/// Double-valued integrals of a slave face (rows: nodes) against a master face.
FacePairIntegrals<double> face_pair_integrals(const SegmentNodes& slave, const SegmentNodes& master,
                                              Multipliers kind);

/// ∂g̃_j/∂x (4.80), 4 × 24, columns: slave nodes 1–4 then master nodes 1–4, 3 per node; forward-mode
/// dual numbers through the clipping, the fan, the inverse maps and the dual coefficients.
Eigen::Matrix<double, 4, 24> weighted_gap_jacobian(const SegmentNodes& slave, const SegmentNodes& master,
                                                   Multipliers kind);

}  // namespace stoss::contact::mortar
