#include "core/contact/penalty/penalty_element.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>

#include "core/contact/geometry/variations.hpp"

namespace stoss::contact {
namespace {

/// |g_{n+1} − g_n| below this × face size: "dd" falls back to ε_N min(g_m, 0) (§5.2 item 2).
constexpr double degenerate_gap_step = 1e-14;

/// ∂m_αβ/∂x at one configuration (entries [α][β]).
using MetricGradient = std::array<std::array<RowVector15, 2>, 2>;

Projection project(const Vector15& x, const Eigen::Vector2d& xi_start) {
  return closest_point_projection(slave_position(x), segment_nodes(x), xi_start);
}

/// ℓ = sqrt(½ |d_1 × d_2|), d_1, d_2 the diagonals of the master segment (its area for a flat face).
double face_size(const Vector15& x) {
  const SegmentNodes y = segment_nodes(x);
  const Eigen::Vector3d d1 = (y.row(2) - y.row(0)).transpose(), d2 = (y.row(3) - y.row(1)).transpose();
  return std::sqrt(0.5 * d1.cross(d2).norm());
}

/// t_N and ∂t_N/∂x_{n+1}.
struct NormalTraction {
  double value = 0;
  RowVector15 gradient = RowVector15::Zero();
};

/// "mid": t_N = ε_N min(g_m, 0) (5.1) at x_m; ∂x_m/∂x_{n+1} = ½.
NormalTraction midpoint_normal_traction(double eps, double g_m, const Vector15& Ns_m) {
  if (!(g_m < 0)) return {};
  return {eps * g_m, 0.5 * eps * Ns_m.transpose()};  // (5.1)
}

/// "dd": t_N = (W_N(g_1) − W_N(g_n)) / (g_1 − g_n) (§5.2 item 2), in cancellation-free form.
NormalTraction discrete_derivative_normal_traction(double eps, double g_n, double g_m, double g_1,
                                                   const Vector15& Ns_m, const Vector15& Ns_1, double size) {
  if (!(g_n < 0 || g_1 < 0)) return {};
  if (g_n <= 0 && g_1 <= 0) return {0.5 * eps * (g_n + g_1), 0.5 * eps * Ns_1.transpose()};  // = quotient
  const double dg = g_1 - g_n;
  if (std::abs(dg) < degenerate_gap_step * size) return midpoint_normal_traction(eps, g_m, Ns_m);
  const double t = (normal_penalty_energy(eps, g_1) - normal_penalty_energy(eps, g_n)) / dg;  // §5.2 item 2
  const double dt_dg1 = (eps * std::min(g_1, 0.0) - t) / dg;  // ∂/∂g_{n+1}
  return {t, dt_dg1 * Ns_1.transpose()};                      // ∂g_1 = N_s(x_1)
}

/// ∂m_αβ/∂x = τ_α·∂τ_β + τ_β·∂τ_α (3.3), (3.8).
MetricGradient metric_gradient(const SegmentFrame& f, const std::array<Matrix3x15, 2>& dtau) {
  MetricGradient dm;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) dm[a][b] = f.tau(a).transpose() * dtau[b] + f.tau(b).transpose() * dtau[a];
  return dm;
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
  const MetricGradient dm = metric_gradient(f, v.dtau);
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

/// Trial state and return map (5.3) with the derivative of t_{n+1} w.r.t. x_{n+1}.
struct TangentialTraction {
  bool slip = false;
  Eigen::Vector2d transported = Eigen::Vector2d::Zero();  ///< t̃_{n,α}
  Eigen::Vector2d value = Eigen::Vector2d::Zero();        ///< t_{n+1,α}
  Eigen::Vector2d slip_increment = Eigen::Vector2d::Zero();
  Matrix2x15 gradient = Matrix2x15::Zero();
};

/// Inputs of the return map: the midpoint frame with its gradients (w.r.t. x_{n+1}, i.e. ½ ∂/∂x_m),
/// D(x_{n+1}) and Δξ.
struct TangentialKinematics {
  const SegmentFrame& mid;
  const std::array<Matrix3x15, 2>& dtau;  ///< ∂τ_α(x_m)/∂x_{n+1}
  const MetricGradient& dm;               ///< ∂m_αβ(x_m)/∂x_{n+1}
  const Matrix2x15& D_1;                  ///< ∂ξ_{n+1}/∂x_{n+1}
  Eigen::Vector2d dxi;                    ///< Δξ = ξ_{n+1} − ξ_n
};

TangentialTraction return_map(const TangentialKinematics& k, const Eigen::Vector3d& history,
                              const NormalTraction& normal, const PenaltyParameters& p) {
  TangentialTraction out;
  const double eps = p.tangential_stiffness;
  if (!(eps > 0)) return out;
  const Eigen::Matrix2d& m = k.mid.metric;
  Matrix2x15 dtr;
  for (int a = 0; a < 2; ++a) {
    out.transported[a] = history.dot(k.mid.tau(a));  // t̃_{n,α} = t_{T,n}·τ_α (§5.2 item 3)
    dtr.row(a) = history.transpose() * k.dtau[a] + eps * (k.dm[a][0] * k.dxi[0] + k.dm[a][1] * k.dxi[1]);
  }
  const Eigen::Vector2d trial = out.transported + eps * m * k.dxi;  // (5.3)
  dtr += eps * m * k.D_1;                                           // ∂(5.3)
  const Eigen::Vector2d q = k.mid.metric_inv * trial;
  const double norm = std::sqrt(trial.dot(q));  // ‖t^tr‖ (5.1)
  const double pressure = -normal.value;        // p = |t_N|
  if (norm - p.friction * pressure <= 0) {      // Φ^tr ≤ 0: stick (5.3)
    out.value = trial;
    out.gradient = dtr;
    return out;
  }
  out.slip = true;
  const double scale = p.friction * pressure / norm;
  out.value = scale * trial;                                          // (5.3)
  out.slip_increment = k.mid.metric_inv * (trial - out.value) / eps;  // Δξ_p (5.3)
  RowVector15 q_dm_q = RowVector15::Zero();
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) q_dm_q += q[a] * q[b] * k.dm[a][b];
  const RowVector15 dnorm =
      (q.transpose() * dtr - 0.5 * q_dm_q) / norm;  // ∂‖t^tr‖, ∂m^{-1} = −m^{-1}∂m m^{-1}
  const RowVector15 dpressure = -normal.gradient;
  out.gradient = (p.friction / norm) * trial * dpressure + scale * (dtr - trial * dnorm / norm);  // ∂(5.3)
  return out;
}

/// Midpoint gradients w.r.t. x_{n+1}: x_m = (x_n + x_{n+1})/2 gives the factor ½.
struct HalfGradients {
  std::array<Matrix3x15, 2> dtau;  ///< ½ ∂τ_α/∂x_m (3.8)
  MetricGradient dm;               ///< ½ ∂m_αβ/∂x_m
};

HalfGradients half_gradients(const SegmentFrame& mid, const GapVariations& v) {
  HalfGradients h{{0.5 * v.dtau[0], 0.5 * v.dtau[1]}, metric_gradient(mid, v.dtau)};
  for (auto& row : h.dm)
    for (RowVector15& entry : row) entry *= 0.5;
  return h;
}

/// Fills a closed step: tractions, force (5.2) at x_m, its tangent w.r.t. x_{n+1}, the new history
/// and the energies (§5.2 items 5–7).
void fill_closed_step(PenaltyResult& out, const GapVariations& mid, const NormalTraction& normal,
                      const TangentialTraction& tangential, const PenaltyParameters& p) {
  const SegmentFrame& f = out.at_m.frame;
  out.closed = true;
  out.slip = tangential.slip;
  out.normal_traction = normal.value;
  out.traction = tangential.value;  // t_alg = t_{n+1} (§5.2 item 5)
  out.transported_traction = tangential.transported;
  out.slip_increment = tangential.slip_increment;
  out.force = normal.value * mid.Ns + mid.D.transpose() * tangential.value;             // (5.2)
  out.tangent = mid.Ns * normal.gradient + 0.5 * normal.value * mid.dNs                 // ∂(t_N N_s), (3.9)
                + mid.D.transpose() * tangential.gradient                               // ∂t_α D_α
                + 0.5 * contracted_xi_hessian(f, out.at_m.gap, mid, tangential.value);  // t_α ∂D_α
  const Eigen::Vector2d contravariant = f.metric_inv * tangential.value;
  out.history_after.traction = contravariant[0] * f.tau1 + contravariant[1] * f.tau2;  // §5.2 item 7
  out.normal_energy = normal_penalty_energy(p.normal_stiffness, out.at_1.gap - p.gap_offset);  // (5.1)
  out.tangential_energy = tangential_penalty_energy(tangential.value, f.metric_inv, p.tangential_stiffness);
  out.slip_work = tangential.slip ? tangential.value.dot(tangential.slip_increment) : 0.0;  // §5.2 item 7
}

PenaltyResult open_result(PenaltyResult out, const PenaltyParameters& p) {
  if (out.at_1.converged) out.normal_energy = normal_penalty_energy(p.normal_stiffness, out.at_1.gap - p.gap_offset);
  return out;  // (5.1)
}

}  // namespace

double normal_penalty_energy(double normal_stiffness, double gap) {
  const double closure = std::min(gap, 0.0);
  return 0.5 * normal_stiffness * closure * closure;  // (5.1)
}

double tangential_penalty_energy(const Eigen::Vector2d& traction, const Eigen::Matrix2d& metric_inv,
                                 double tangential_stiffness) {
  if (!(tangential_stiffness > 0)) return 0;
  return traction.dot(metric_inv * traction) / (2 * tangential_stiffness);  // (5.1)
}

double penalty_default_stiffness(double youngs_modulus, double face_size) {
  return 10 * youngs_modulus * face_size;  // §5.1 [choice]
}

PenaltyResult penalty_element(const Vector15& x_n, const Vector15& x_1, const FrictionHistory& history,
                              const PenaltyParameters& p, const Eigen::Vector2d& xi_start) {
  PenaltyResult out;
  out.at_n = project(x_n, xi_start);  // §5.2 item 1
  out.at_m = project(0.5 * (x_n + x_1), xi_start);
  out.at_1 = project(x_1, xi_start);
  if (!(out.at_n.converged && out.at_m.converged && out.at_1.converged))
    return open_result(out, p);

  const GapVariations mid = gap_variations(out.at_m.frame, out.at_m.gap);  // (3.6)–(3.9) at x_m
  const Vector15 Ns_1 = gap_gradient(out.at_1.frame);                      // (3.6) at x_{n+1}
  const NormalTraction normal =
      p.normal_rule == NormalRule::midpoint
          ? midpoint_normal_traction(p.normal_stiffness, out.at_m.gap - p.gap_offset, mid.Ns)
          : discrete_derivative_normal_traction(p.normal_stiffness, out.at_n.gap - p.gap_offset,
                                                out.at_m.gap - p.gap_offset, out.at_1.gap - p.gap_offset,
                                                mid.Ns, Ns_1, face_size(x_n));
  if (!(normal.value < 0)) return open_result(out, p);  // open: reset t_T (§5.2 item 7)

  const HalfGradients half = half_gradients(out.at_m.frame, mid);
  const Matrix2x15 D_1 = xi_gradient(out.at_1.frame, out.at_1.gap);  // (3.7) at x_{n+1}
  const TangentialKinematics kinematics{out.at_m.frame, half.dtau, half.dm, D_1, out.at_1.xi - out.at_n.xi};
  const TangentialTraction tangential = return_map(kinematics, history.traction, normal, p);  // (5.3)
  fill_closed_step(out, mid, normal, tangential, p);
  return out;
}

}  // namespace stoss::contact
