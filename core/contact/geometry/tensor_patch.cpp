#include "core/contact/geometry/tensor_patch.hpp"

namespace stoss::contact {
namespace {
// Ascending coefficients in t ∈ [−1, 1] (docs/smooth_master_surface.md (2.1)).
constexpr double bilinear_factors[2][4] = {{0.5, -0.5, 0, 0}, {0.5, 0.5, 0, 0}};
// Uniform cubic B-spline segment with u = (1 + t)/2: (1−u)³/6, (3u³ − 6u² + 4)/6,
// (−3u³ + 3u² + 3u + 1)/6, u³/6, expanded in t.
constexpr double bspline_factors[4][4] = {{1.0 / 48, -3.0 / 48, 3.0 / 48, -1.0 / 48},
                                          {23.0 / 48, -15.0 / 48, -3.0 / 48, 3.0 / 48},
                                          {23.0 / 48, 15.0 / 48, -3.0 / 48, -3.0 / 48},
                                          {1.0 / 48, 3.0 / 48, 3.0 / 48, 1.0 / 48}};

double second_derivative(const double* c, double t) {
  return 2 * c[2] + 6 * c[3] * t;
}

/// Node values of the slot values B_s = u_i v_j for per-direction derivative orders (du, dv).
Eigen::VectorXd tensor_nodes(const TensorPatch& p, const Eigen::Vector2d& xi, int du, int dv) {
  const int n = p.factors();
  std::vector<double> B(n * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      B[i + n * j] = factor(p.family, i, xi[0], du) * factor(p.family, j, xi[1], dv);
  return as_vector(detail::to_nodes(p, B));
}
}  // namespace

const double* factor_coefficients(PatchFamily family, int i) {
  return family == PatchFamily::bilinear ? bilinear_factors[i] : bspline_factors[i];
}

double factor(PatchFamily family, int i, double t, int derivative) {
  const double* c = factor_coefficients(family, i);
  if (derivative == 0) return polynomial(c, t);
  if (derivative == 1) return polynomial_slope(c, t);
  if (derivative == 2) return second_derivative(c, t);
  return 6 * c[3];
}

BasisCurvatures patch_curvatures(const TensorPatch& p, const Eigen::Vector2d& xi) {
  if (p.pieces) {  // N_{,αβ} = scale² Σ R_γα R_δβ G_{,γδ} on the piece that holds ξ (2.6)
    const ExtraordinaryPieces& e = *p.pieces;
    const detail::PieceLocation l = detail::locate(e, xi);
    const auto s = detail::to_piece(e, l, xi[0], xi[1]);
    const BasisCurvatures g = patch_curvatures(e.rings[l.ring - 1][l.square], {s[0], s[1]});
    const Eigen::Matrix2d J = l.scale * detail::corner_rotation(e.corner);  // ∂s/∂ξ
    const auto second = [&](int a, int b) {
      return Eigen::VectorXd(J(0, a) * J(0, b) * g.N11 + (J(0, a) * J(1, b) + J(1, a) * J(0, b)) * g.N12 +
                             J(1, a) * J(1, b) * g.N22);
    };
    return {second(0, 0), second(0, 1), second(1, 1)};
  }
  const int n = p.factors();
  std::vector<double> B11(n * n), B12(n * n), B22(n * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double u = factor(p.family, i, xi[0], 0), du = factor(p.family, i, xi[0], 1);
      const double v = factor(p.family, j, xi[1], 0), dv = factor(p.family, j, xi[1], 1);
      B11[i + n * j] = factor(p.family, i, xi[0], 2) * v;
      B12[i + n * j] = du * dv;
      B22[i + n * j] = u * factor(p.family, j, xi[1], 2);
    }
  const auto nodes = [&p](const std::vector<double>& slots) { return as_vector(detail::to_nodes(p, slots)); };
  return {nodes(B11), nodes(B12), nodes(B22)};
}

BasisThirdDerivatives patch_third_derivatives(const TensorPatch& p, const Eigen::Vector2d& xi) {
  if (p.pieces) {  // N_{,αβγ} = Σ J_δα J_εβ J_ζγ G_{,δεζ} on the piece that holds ξ, J = ∂s/∂ξ (2.6)
    const ExtraordinaryPieces& e = *p.pieces;
    const detail::PieceLocation l = detail::locate(e, xi);
    const auto s = detail::to_piece(e, l, xi[0], xi[1]);
    const BasisThirdDerivatives g = patch_third_derivatives(e.rings[l.ring - 1][l.square], {s[0], s[1]});
    const Eigen::VectorXd* G[4] = {&g.N111, &g.N112, &g.N122, &g.N222};  // by the number of 2s
    const Eigen::Matrix2d J = l.scale * detail::corner_rotation(e.corner);
    const auto third = [&](int a, int b, int c) {
      Eigen::VectorXd out = Eigen::VectorXd::Zero(g.N111.size());
      for (int d = 0; d < 2; ++d)
        for (int f = 0; f < 2; ++f)
          for (int k = 0; k < 2; ++k) out += J(d, a) * J(f, b) * J(k, c) * *G[d + f + k];
      return out;
    };
    return {third(0, 0, 0), third(0, 0, 1), third(0, 1, 1), third(1, 1, 1)};
  }
  return {tensor_nodes(p, xi, 3, 0), tensor_nodes(p, xi, 2, 1), tensor_nodes(p, xi, 1, 2),
          tensor_nodes(p, xi, 0, 3)};
}

Eigen::Vector3d combine_nodes(const TensorPatch& p, const Eigen::VectorXd& c, const Eigen::VectorXd& x) {
  Eigen::Vector3d y = Eigen::Vector3d::Zero();
  for (int K = 0; K < p.size(); ++K) y += c[K] * x.segment<3>(3 * p.nodes[K]);
  return y;
}

TensorPatch bilinear_patch(const std::array<int, 4>& face) {
  TensorPatch p;
  p.family = PatchFamily::bilinear;
  p.nodes.assign(face.begin(), face.end());
  // Corner K at (−1,−1), (1,−1), (1,1), (−1,1): slots s = i + 2j = 0, 1, 3, 2.
  p.weights = Eigen::MatrixXd::Zero(4, 4);
  p.weights(0, 0) = p.weights(1, 1) = p.weights(2, 3) = p.weights(3, 2) = 1;
  return p;
}

}  // namespace stoss::contact
