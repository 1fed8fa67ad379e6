#include "core/contact/penalty/penalty_element.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>

#include "core/contact/geometry/variations.hpp"

namespace stoss::contact {
namespace {

using namespace penalty_law;
using MetricGradient15 = MetricGradient<15>;

Projection project(const Vector15& x, const Eigen::Vector2d& xi_start) {
  return closest_point_projection(slave_position(x), segment_nodes(x), xi_start);
}

/// ℓ = sqrt(½ |d_1 × d_2|), d_1, d_2 the diagonals of the master segment (its area for a flat face).
double face_size(const Vector15& x) {
  const SegmentNodes y = segment_nodes(x);
  const Eigen::Vector3d d1 = (y.row(2) - y.row(0)).transpose(), d2 = (y.row(3) - y.row(1)).transpose();
  return std::sqrt(0.5 * d1.cross(d2).norm());
}

/// ∂(r·y_{,12})/∂x at the CPP, r = g_N n: (n·y_{,12}) N_s + g_N (y_{,12}·∂n + n·∂y_{,12}) (3.4).
RowVector15 curvature_gradient(const SegmentFrame& f, double gap, const GapVariations& v) {
  RowVector15 dc = f.normal.dot(f.y12) * v.Ns.transpose() + gap * f.y12.transpose() * v.dn;
  for (int K = 0; K < 4; ++K) dc.segment<3>(3 + 3 * K) += gap * f.d2N12[K] * f.normal.transpose();
  return dc;
}

/// Σ_α t_α ∂D_α/∂x at fixed covariant t: the derivative of (3.7), D = A^{-1} B, B_β = T_β + g_N N̄_β,
///   Σ_α t_α ∂D_α = Σ_β s_β ∂B_β − Σ_γ D_γ ⊗ (Σ_β s_β ∂A_βγ),   s = A^{-1} t (A symmetric).
Matrix15 contracted_xi_hessian(const SegmentFrame& f, double gap, const GapVariations& v,
                               const Eigen::Vector2d& t) {
  const MetricGradient15 dm = metric_gradient<15>(f, v.dtau);
  const Eigen::Matrix2d A = projection_matrix(f, gap * f.normal);  // (3.4) at the CPP
  const Eigen::Vector2d s = A.inverse() * t;
  const Matrix2x15 Nbar = normal_variation(f);           // (3.7)
  Matrix15 H = Nbar.transpose() * s * v.Ns.transpose();  // Σ_β s_β N̄_β ⊗ ∂g_N
  for (int b = 0; b < 2; ++b) {
    H.topRows<3>() += s[b] * v.dtau[b];  // ∂T_β, slave block: ∂τ_β (3.8)
    for (int K = 0; K < 4; ++K) {
      const RowVector15 dNK = f.dN.row(K) * v.D;             // ∂N_K = N_{K,α} D_α
      const RowVector15 dNKb = f.d2N12[K] * v.D.row(1 - b);  // ∂N_{K,β} = N_{K,12} D_{γ≠β}
      H.middleRows<3>(3 + 3 * K) += s[b] * (-f.N[K] * v.dtau[b] - f.tau(b) * dNK             // ∂T_β (3.7)
                                            + gap * (f.dN(K, b) * v.dn + f.normal * dNKb));  // g_N ∂N̄_β (3.7)
    }
  }
  const RowVector15 dc = curvature_gradient(f, gap, v);
  for (int c = 0; c < 2; ++c) {
    const RowVector15 s_dA = s[0] * dm[0][c] + s[1] * dm[1][c] - s[1 - c] * dc;  // Σ_β s_β ∂A_βγ (3.4)
    H -= v.D.row(c).transpose() * s_dA;
  }
  return H;
}

}  // namespace

double penalty_default_stiffness(double youngs_modulus, double face_size) {
  return 10 * youngs_modulus * face_size;  // §5.1 [choice]
}

double normal_penalty_energy(double normal_stiffness, double gap) {
  const double closure = std::min(gap, 0.0);
  return 0.5 * normal_stiffness * closure * closure;  // (5.1)
}

double tangential_penalty_energy(const Eigen::Vector2d& traction, const Eigen::Matrix2d& metric_inv,
                                 double tangential_stiffness) {
  if (!(tangential_stiffness > 0)) return 0;
  return traction.dot(metric_inv * traction) / (2 * tangential_stiffness);  // (5.1)
}

PenaltyResult penalty_element(const Vector15& x_n, const Vector15& x_1, const FrictionHistory& history,
                              const PenaltyParameters& p, const Eigen::Vector2d& xi_start) {
  PenaltyResult out;
  out.at_n = project(x_n, xi_start);  // §5.2 item 1
  out.at_1 = project(x_1, xi_start);
  out.at_m = p.at_end ? out.at_1 : project(0.5 * (x_n + x_1), xi_start);  // §5b.6: x_{n+1} in static steps
  if (!(out.at_n.converged && out.at_m.converged && out.at_1.converged)) return open_result(out, p);

  const GapVariations mid = gap_variations(out.at_m.frame, out.at_m.gap);  // (3.6)–(3.9) at x_m
  const Vector15 Ns_1 = gap_gradient(out.at_1.frame);                      // (3.6) at x_{n+1}
  const NormalTraction<15> normal =
      normal_traction<15>(p, out.at_n, out.at_m, out.at_1, mid.Ns, Ns_1, face_size(x_n));
  if (!(normal.value < 0)) return open_result(out, p);  // open: reset t_T (§5.2 item 7)

  const double theta = evaluation_weight(p);
  const PointGradients<15> at_point = point_gradients<15>(out.at_m.frame, mid.dtau, theta);
  const Matrix2x15 D_1 = xi_gradient(out.at_1.frame, out.at_1.gap);  // (3.7) at x_{n+1}
  const TangentialKinematics<15> kinematics{out.at_m.frame, at_point, D_1, out.at_1.xi - out.at_n.xi};
  const TangentialTraction<15> tangential = return_map(kinematics, history.traction, normal, p);  // (5.3)
  const Matrix15 xi_hessian = contracted_xi_hessian(out.at_m.frame, out.at_m.gap, mid, tangential.value);
  fill_closed_step<15>(out, {mid.Ns, mid.dNs, mid.D, theta}, xi_hessian, normal, tangential, p);
  return out;
}

}  // namespace stoss::contact
