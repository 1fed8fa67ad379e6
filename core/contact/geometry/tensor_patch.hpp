#pragma once
/// @file Master surface patches whose points are linear in the master nodes (docs/smooth_master_surface.md
/// §2): y(ξ) = Σ_K N_K(ξ) y_K with N_K(ξ) = Σ_s W_Ks B_s(ξ), where the slot functions
/// B_s(ξ) = b_i(ξ¹) b_j(ξ²) (s = i + n j) are tensor products of n univariate polynomials of degree
/// ≤ 3 on the face's ξ ∈ [−1, 1]², extended beyond it by the same polynomials. A bilinear face
/// (n = 2, W = identity) and a uniform cubic B-spline patch over a face's 4×4 neighbourhood (n = 4,
/// ghost slots at a surface rim folded into W) share this form, and so do every kernel built on it.
///
/// Scalar type T: double, or Dual (a value with its gradient with respect to two parameters) where a
/// kernel needs derivatives of the evaluation with respect to ξ_{n+1}.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

namespace stoss::contact {

/// The univariate factors of a patch.
enum class PatchFamily {
  bilinear,       ///< b_0 = (1 − t)/2, b_1 = (1 + t)/2
  cubic_bspline,  ///< uniform cubic B-spline segment, t = 2u − 1 (docs/smooth_master_surface.md (2.1))
};

struct ExtraordinaryPieces;

/// One patch: M master nodes and the M × n² slot weights (Σ_K W_Ks = 1 for every slot s, so that
/// Σ_K N_K ≡ 1: translations are reproduced, which the invariant form of §4.3 relies on).
/// @note A face with an extraordinary corner is piecewise (docs/smooth_master_surface.md §2.5):
///       `pieces` then holds its regular B-spline pieces, each over the same M nodes, and the
///       evaluations below pick the piece that holds ξ; `weights` is unused.
struct TensorPatch {
  PatchFamily family = PatchFamily::bilinear;
  std::vector<int> nodes;   ///< global node ids, K = 0 … M−1 (K = 0 is the reference node y_1)
  Eigen::MatrixXd weights;  ///< W (M × n²)
  std::shared_ptr<const ExtraordinaryPieces> pieces;  ///< null on a regular face
  int size() const { return static_cast<int>(nodes.size()); }
  int factors() const { return family == PatchFamily::bilinear ? 2 : 4; }
};

/// The Catmull–Clark limit surface of a face whose corner `corner` is an extraordinary vertex, as
/// rings of regular pieces (docs/smooth_master_surface.md §2.5). In the face's coordinates turned so
/// that the vertex is at ξ' = (−1, −1), with u = (ξ'¹ + 1)/2, v = (ξ'² + 1)/2: ring n (n = 1, 2, …)
/// covers max(u, v) ∈ [2⁻ⁿ, 2¹⁻ⁿ], in three squares of side 2⁻ⁿ: q = 0 at u ≥ ½·2¹⁻ⁿ > v, q = 1 at
/// both ≥ ½·2¹⁻ⁿ, q = 2 at v ≥ ½·2¹⁻ⁿ > u. Each square is a bicubic B-spline piece over the face's M
/// nodes (by subdividing n times).
struct ExtraordinaryPieces {
  int corner = 0;                                 ///< the face corner (0–3) at the vertex
  std::vector<std::array<TensorPatch, 3>> rings;  ///< rings[n − 1][q]
};

/// A value and its gradient with respect to two parameters (forward-mode differentiation of patch
/// evaluations with respect to ξ_{n+1}).
struct Dual {
  double v = 0;
  Eigen::Vector2d g = Eigen::Vector2d::Zero();
  Dual() = default;
  Dual(double value) : v(value) {}  // NOLINT: constants mix freely with duals
  Dual(double value, const Eigen::Vector2d& grad) : v(value), g(grad) {}
};
inline Dual operator+(const Dual& a, const Dual& b) {
  return {a.v + b.v, a.g + b.g};
}
inline Dual operator-(const Dual& a, const Dual& b) {
  return {a.v - b.v, a.g - b.g};
}
inline Dual operator-(const Dual& a) {
  return {-a.v, -a.g};
}
inline Dual operator*(const Dual& a, const Dual& b) {
  return {a.v * b.v, a.g * b.v + a.v * b.g};
}
inline Dual operator/(const Dual& a, const Dual& b) {
  return {a.v / b.v, (a.g * b.v - a.v * b.g) / (b.v * b.v)};
}
inline Dual& operator+=(Dual& a, const Dual& b) {
  return a = a + b;
}

inline double value_of(double x) {
  return x;
}
inline double value_of(const Dual& x) {
  return x.v;
}

/// Per node K: N_K, N_{K,1}, N_{K,2} (or divided differences of them, see patch_divided).
template <class T>
struct BasisValues {
  std::vector<T> N, N1, N2;
};

/// Second derivatives N_{K,11}, N_{K,12}, N_{K,22}.
struct BasisCurvatures {
  Eigen::VectorXd N11, N12, N22;
};

/// Third derivatives N_{K,111}, N_{K,112}, N_{K,122}, N_{K,222}.
struct BasisThirdDerivatives {
  Eigen::VectorXd N111, N112, N122, N222;
};

/// Univariate factor i of `family` at t: value, first, second and third derivative.
double factor(PatchFamily family, int i, double t, int derivative);

/// The polynomial coefficients (degree ≤ 3, ascending) of factor i of `family`.
const double* factor_coefficients(PatchFamily family, int i);

/// p(t), p'(t) for p with ascending coefficients c (degree ≤ 3).
template <class T>
T polynomial(const double* c, const T& t) {
  return c[0] + t * (c[1] + t * (c[2] + t * c[3]));
}
template <class T>
T polynomial_slope(const double* c, const T& t) {
  return c[1] + t * (2 * c[2] + t * (3 * c[3]));
}
/// (p(b) − p(a))/(b − a) in closed form: exact for every a, b, equal to p'(a) at a = b.
template <class T>
T polynomial_divided(const double* c, const T& a, const T& b) {
  return c[1] + c[2] * (a + b) + c[3] * (a * a + a * b + b * b);
}
/// (p'(b) − p'(a))/(b − a).
template <class T>
T polynomial_slope_divided(const double* c, const T& a, const T& b) {
  return 2 * c[2] + 3 * c[3] * (a + b);
}

namespace detail {
/// Maps slot values to node values: out_K = Σ_s W_Ks slot_s.
template <class T>
std::vector<T> to_nodes(const TensorPatch& p, const std::vector<T>& slot) {
  std::vector<T> out(p.size(), T(0.0));
  for (int K = 0; K < p.size(); ++K)
    for (size_t s = 0; s < slot.size(); ++s)
      if (p.weights(K, s) != 0) out[K] += p.weights(K, s) * slot[s];
  return out;
}

/// Per factor i of one direction: f_i and f_i' at t (or their divided differences).
template <class T>
struct FactorColumn {
  std::vector<T> f, df;
};

template <class T>
FactorColumn<T> factors_at(PatchFamily family, int n, const T& t) {
  FactorColumn<T> c{std::vector<T>(n), std::vector<T>(n)};
  for (int i = 0; i < n; ++i) {
    c.f[i] = polynomial(factor_coefficients(family, i), t);
    c.df[i] = polynomial_slope(factor_coefficients(family, i), t);
  }
  return c;
}

template <class T>
FactorColumn<T> factors_divided(PatchFamily family, int n, const T& a, const T& b) {
  FactorColumn<T> c{std::vector<T>(n), std::vector<T>(n)};
  for (int i = 0; i < n; ++i) {
    c.f[i] = polynomial_divided(factor_coefficients(family, i), a, b);
    c.df[i] = polynomial_slope_divided(factor_coefficients(family, i), a, b);
  }
  return c;
}

/// Node values of B_s = u_i v_j, B_{s,1} = u'_i v_j, B_{s,2} = u_i v'_j from the two columns.
template <class T>
BasisValues<T> tensor(const TensorPatch& p, const FactorColumn<T>& u, const FactorColumn<T>& v) {
  const int n = p.factors();
  std::vector<T> B(n * n), B1(n * n), B2(n * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      B[i + n * j] = u.f[i] * v.f[j];
      B1[i + n * j] = u.df[i] * v.f[j];
      B2[i + n * j] = u.f[i] * v.df[j];
    }
  return {to_nodes(p, B), to_nodes(p, B1), to_nodes(p, B2)};
}
}  // namespace detail

namespace detail {
/// The rotation R with ξ' = R ξ that takes face corner k to corner 0 (docs/smooth_master_surface.md (2.6)).
inline Eigen::Matrix2d corner_rotation(int k) {
  Eigen::Matrix2d R = Eigen::Matrix2d::Identity(), quarter;
  quarter << 0, 1, -1, 0;
  for (int i = 0; i < k; ++i) R = quarter * R;
  return R;
}

/// Where a point of a piecewise face lies: ring n, square q, and the affine map ξ → s of the piece
/// (s = scale R ξ + shift, scale = 2ⁿ).
struct PieceLocation {
  int ring = 1, square = 1;
  double scale = 2;
  Eigen::Vector2d shift = Eigen::Vector2d::Zero();
  bool operator==(const PieceLocation& o) const { return ring == o.ring && square == o.square; }
};

inline PieceLocation locate(const ExtraordinaryPieces& e, const Eigen::Vector2d& xi) {
  const Eigen::Vector2d r = corner_rotation(e.corner) * xi;
  const double u = 0.5 * (r[0] + 1), v = 0.5 * (r[1] + 1), m = std::max(u, v);
  const int last = static_cast<int>(e.rings.size());
  PieceLocation l;
  l.ring = m >= 0.5                      ? 1
           : m <= std::ldexp(1.0, -last) ? last
                                         : std::min(last, 1 + static_cast<int>(std::floor(-std::log2(m))));
  const double half = std::ldexp(1.0, -l.ring);  // ½ · 2¹⁻ⁿ
  const bool right = u >= half, top = v >= half;
  l.square = right && top ? 1 : right ? 0 : top ? 2 : (u >= v ? 0 : 2);
  const double au = l.square <= 1 ? half : 0, av = l.square >= 1 ? half : 0;
  // s = 2 (u − a_u)/2⁻ⁿ − 1 with u = (r + 1)/2: s = 2ⁿ r + 2ⁿ − 2ⁿ⁺¹ a_u − 1.
  l.scale = std::ldexp(1.0, l.ring);
  l.shift = Eigen::Vector2d(l.scale - 2 * l.scale * au - 1, l.scale - 2 * l.scale * av - 1);
  return l;
}

template <class T>
std::array<T, 2> to_piece(const ExtraordinaryPieces& e, const PieceLocation& l, const T& xi1, const T& xi2) {
  const Eigen::Matrix2d R = corner_rotation(e.corner);
  return {T(l.scale) * (R(0, 0) * xi1 + R(0, 1) * xi2) + T(l.shift[0]),
          T(l.scale) * (R(1, 0) * xi1 + R(1, 1) * xi2) + T(l.shift[1])};
}

/// Face derivatives from piece derivatives: ∂/∂ξ_α = scale Σ_β R_βα ∂/∂s_β.
template <class T>
void to_face_derivatives(const ExtraordinaryPieces& e, double scale, BasisValues<T>& b) {
  const Eigen::Matrix2d R = corner_rotation(e.corner);
  for (size_t K = 0; K < b.N.size(); ++K) {
    const T s1 = b.N1[K], s2 = b.N2[K];
    b.N1[K] = T(scale * R(0, 0)) * s1 + T(scale * R(1, 0)) * s2;
    b.N2[K] = T(scale * R(0, 1)) * s1 + T(scale * R(1, 1)) * s2;
  }
}
}  // namespace detail

template <class T>
BasisValues<T> patch_values(const TensorPatch& p, const T& xi1, const T& xi2);

namespace detail {
template <class T>
BasisValues<T> piecewise_values(const TensorPatch& p, const T& xi1, const T& xi2) {
  const ExtraordinaryPieces& e = *p.pieces;
  const PieceLocation l = locate(e, {value_of(xi1), value_of(xi2)});
  const auto s = to_piece(e, l, xi1, xi2);
  BasisValues<T> b = patch_values(e.rings[l.ring - 1][l.square], s[0], s[1]);
  to_face_derivatives(e, l.scale, b);
  return b;
}
}  // namespace detail

/// N_K, N_{K,1}, N_{K,2} at ξ = (xi1, xi2).
template <class T>
BasisValues<T> patch_values(const TensorPatch& p, const T& xi1, const T& xi2) {
  if (p.pieces) return detail::piecewise_values(p, xi1, xi2);
  const int n = p.factors();
  return detail::tensor(p, detail::factors_at(p.family, n, xi1), detail::factors_at(p.family, n, xi2));
}

/// Divided differences in one direction at a fixed other coordinate (docs/smooth_master_surface.md
/// (3.4)): direction 0 gives [F(b, c) − F(a, c)]/(b − a) for F = N_K, N_{K,1}, N_{K,2}; direction 1
/// gives [F(c, b) − F(c, a)]/(b − a). Exact for every a, b (polynomial closed forms, no subtraction).
template <class T>
BasisValues<T> patch_divided(const TensorPatch& p, int direction, const T& a, const T& b, const T& c);

namespace detail {
/// Divided differences on a piecewise face: exact within one piece (the piece's closed forms, mapped);
/// between pieces the difference quotient of the values, or, for endpoints closer than 1e-6 of a
/// piece, the first endpoint's piece continued (the limit surface is C² there, so its error is
/// O(Δ³) of the third-derivative jump).
template <class T>
BasisValues<T> piecewise_divided(const TensorPatch& p, int direction, const T& a, const T& b, const T& c) {
  const ExtraordinaryPieces& e = *p.pieces;
  const auto point = [&](const T& t) {
    return direction == 0 ? Eigen::Vector2d(value_of(t), value_of(c))
                          : Eigen::Vector2d(value_of(c), value_of(t));
  };
  const PieceLocation la = locate(e, point(a)), lb = locate(e, point(b));
  const double gap = std::abs(value_of(b) - value_of(a));
  if (!(la == lb) && gap * la.scale > 1e-6) {
    const BasisValues<T> fa = direction == 0 ? patch_values(p, a, c) : patch_values(p, c, a);
    const BasisValues<T> fb = direction == 0 ? patch_values(p, b, c) : patch_values(p, c, b);
    BasisValues<T> q = fa;
    const T step = b - a;
    for (size_t K = 0; K < fa.N.size(); ++K) {
      q.N[K] = (fb.N[K] - fa.N[K]) / step;
      q.N1[K] = (fb.N1[K] - fa.N1[K]) / step;
      q.N2[K] = (fb.N2[K] - fa.N2[K]) / step;
    }
    return q;
  }
  const Eigen::Matrix2d R = corner_rotation(e.corner);
  const int beta = R(0, direction) != 0 ? 0 : 1;  // the piece direction the face direction maps to
  const double sigma = la.scale * R(beta, direction);
  const auto sa = direction == 0 ? to_piece(e, la, a, c) : to_piece(e, la, c, a);
  const auto sb = direction == 0 ? to_piece(e, la, b, c) : to_piece(e, la, c, b);
  BasisValues<T> q = patch_divided(e.rings[la.ring - 1][la.square], beta, sa[beta], sb[beta], sa[1 - beta]);
  for (size_t K = 0; K < q.N.size(); ++K) {
    q.N[K] = T(sigma) * q.N[K];
    q.N1[K] = T(sigma) * q.N1[K];
    q.N2[K] = T(sigma) * q.N2[K];
  }
  to_face_derivatives(e, la.scale, q);
  return q;
}
}  // namespace detail

template <class T>
BasisValues<T> patch_divided(const TensorPatch& p, int direction, const T& a, const T& b, const T& c) {
  if (p.pieces) return detail::piecewise_divided(p, direction, a, b, c);
  const int n = p.factors();
  const auto divided = detail::factors_divided(p.family, n, a, b);
  const auto fixed = detail::factors_at(p.family, n, c);
  return direction == 0 ? detail::tensor(p, divided, fixed) : detail::tensor(p, fixed, divided);
}

/// Node values as an Eigen vector.
inline Eigen::VectorXd as_vector(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

/// N_{K,11}, N_{K,12}, N_{K,22} at ξ.
BasisCurvatures patch_curvatures(const TensorPatch& p, const Eigen::Vector2d& xi);

/// N_{K,αβγ} at ξ (constant on a piece of degree ≤ 3 per direction; the friction tangent needs them,
/// docs/smooth_master_surface.md §3.8).
BasisThirdDerivatives patch_third_derivatives(const TensorPatch& p, const Eigen::Vector2d& xi);

/// Σ_K c_K y_K for node values c and stacked positions x (3 per global node).
Eigen::Vector3d combine_nodes(const TensorPatch& p, const Eigen::VectorXd& c, const Eigen::VectorXd& x);

/// The bilinear patch of one face (the faceted surface of formulation §3.1 in this form).
TensorPatch bilinear_patch(const std::array<int, 4>& face);

}  // namespace stoss::contact
