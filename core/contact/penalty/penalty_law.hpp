#pragma once
/// @file The penalty law and Coulomb return map of one NTS element over a step (docs/theory.md §5.2,
/// (5.1)–(5.3)), independent of the master surface: the same templates serve the 15-entry element of a
/// bilinear face (N = 15) and the element of a smooth patch with M master nodes (N = Eigen::Dynamic,
/// 3M + 3 entries, docs/smooth_master_surface.md §3.8). Gradients are with respect to x_{n+1}.

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>

#include "core/contact/geometry/projection.hpp"

namespace stoss::contact {

template <int N>
using ElementRow = Eigen::Matrix<double, 1, N>;
template <int N>
using ElementVector = Eigen::Matrix<double, N, 1>;
template <int N>
using ElementMatrix = Eigen::Matrix<double, N, N>;
template <int N>
using ElementRows2 = Eigen::Matrix<double, 2, N>;
template <int N>
using ElementRows3 = Eigen::Matrix<double, 3, N>;

/// Zero of a fixed or dynamic element-sized object with `n` columns (n rows for N × N).
template <class T>
T element_zero(Eigen::Index n) {
  if constexpr (T::RowsAtCompileTime == Eigen::Dynamic && T::ColsAtCompileTime == Eigen::Dynamic)
    return T::Zero(n, n);
  else if constexpr (T::ColsAtCompileTime == Eigen::Dynamic)
    return T::Zero(T::RowsAtCompileTime, n);
  else if constexpr (T::RowsAtCompileTime == Eigen::Dynamic)
    return T::Zero(n, 1);
  else
    return T::Zero();
}

/// Friction history of one element: the spatial tangential traction t_{T,n} (§5.2 item 3).
/// Zero while the contact is open.
struct FrictionHistory {
  Eigen::Vector3d traction = Eigen::Vector3d::Zero();
};

/// How the normal traction of a step is evaluated (§5.2 item 2).
enum class NormalRule {
  discrete_derivative,  ///< "dd" [choice, default]: closed if g_n < 0 or g_{n+1} < 0,
                        ///< t_N = (W_N(g_{n+1}) − W_N(g_n)) / (g_{n+1} − g_n)
  midpoint,             ///< "mid" (seed): closed if g_m < 0, t_N = ε_N g_m
};

/// Penalty and Coulomb parameters of a contact pair (5.1).
struct PenaltyParameters {
  double normal_stiffness = 0;      ///< ε_N > 0 (force/length; t_N is a nodal force)
  double tangential_stiffness = 0;  ///< ε_T ≥ 0; 0 switches the tangential traction off
  double friction = 0;              ///< Coulomb μ ≥ 0
  NormalRule normal_rule = NormalRule::discrete_derivative;
  /// Constant c with W_N = W_N(g_N − c) and t_N from g_N − c: the gap kept at a face switch
  /// (switch_gap "keep", §3.4). Geometry (N_s, D_α, the reported gaps) uses the true g_N.
  double gap_offset = 0;
  /// Static steps (docs/theory.md (5b.7c)): the CPP, t_N = ε_N min(g_{n+1}, 0) and the geometry of (5.2) at
  /// x_{n+1} instead of x_m, so that a converged step is the equilibrium of its load level.
  bool at_end = false;
};

/// ∂x_θ/∂x_{n+1} of the point the element's geometry is evaluated at: x_m (½) or, in static steps, x_{n+1}.
inline double evaluation_weight(const PenaltyParameters& p) {
  return p.at_end ? 1.0 : 0.5;
}

/// One element over one step, for an element vector of N entries [x_s; master nodes].
/// @note When the contact is open (or one of the three CPPs did not converge), `force`, `tangent`,
///       the tractions, `slip_increment`, `tangential_energy` and `slip_work` are zero and
///       `history_after` is reset (§5.2 item 7); `normal_energy` is still W_N(g_{n+1}) when the CPP
///       of x_{n+1} converged (e.g. nonzero for "mid" with g_m ≥ 0 > g_{n+1}).
template <int N>
struct PenaltyResultT {
  bool closed = false;         ///< contact closed in this step per the normal rule (§5.2 item 2)
  bool slip = false;           ///< return map (5.3): slip (true) or stick
  ElementVector<N> force;      ///< t_N N_s(x_m) + t_{n+1,α} D_α(x_m) (5.2); caller multiplies by h
  ElementMatrix<N> tangent;    ///< ∂force/∂x_{n+1} (non-symmetric)
  double normal_traction = 0;  ///< t_N ≤ 0
  Eigen::Vector2d traction = Eigen::Vector2d::Zero();              ///< covariant t_{n+1,α} (5.3)
  Eigen::Vector2d transported_traction = Eigen::Vector2d::Zero();  ///< t̃_{n,α} = t_{T,n}·τ_α(x_m)
  Eigen::Vector2d slip_increment = Eigen::Vector2d::Zero();        ///< Δξ_p (contravariant) (5.3)
  double normal_energy = 0;                                        ///< W_N(g_{n+1}) (5.1)
  double tangential_energy = 0;  ///< W_T(t_{n+1}) = ‖t_{n+1}‖²/(2ε_T), metric at x_m (5.1)
  double slip_work = 0;  ///< t_{n+1}·Δξ_p = μ p ‖Δξ_p‖ ≥ 0; exactly 0 in stick (§5.2 item 7)
  FrictionHistory history_after;  ///< t_{T,n+1} = t_{n+1,α} m^{αβ} τ_β(x_m); commit after convergence
  Projection at_n, at_m, at_1;    ///< CPPs of x_n, x_m = (x_n + x_{n+1})/2 (x_{n+1} if at_end), x_{n+1}

  explicit PenaltyResultT(Eigen::Index n = N == Eigen::Dynamic ? 0 : N)
      : force(element_zero<ElementVector<N>>(n)), tangent(element_zero<ElementMatrix<N>>(n)) {}
};

/// W_N(g) = ½ ε_N min(g, 0)² (5.1).
double normal_penalty_energy(double normal_stiffness, double gap);

/// W_T = ‖t‖²/(2ε_T), ‖t‖² = t_α m^{αβ} t_β (5.1), for covariant t and the inverse metric m^{αβ};
/// 0 when ε_T = 0.
double tangential_penalty_energy(const Eigen::Vector2d& traction, const Eigen::Matrix2d& metric_inv,
                                 double tangential_stiffness);

namespace penalty_law {

/// |g_{n+1} − g_n| below this × face size: "dd" falls back to ε_N min(g_m, 0) (§5.2 item 2).
constexpr double degenerate_gap_step = 1e-14;

/// ∂m_αβ/∂x at one configuration (entries [α][β]).
template <int N>
using MetricGradient = std::array<std::array<ElementRow<N>, 2>, 2>;

/// t_N and ∂t_N/∂x_{n+1}.
template <int N>
struct NormalTraction {
  double value = 0;
  ElementRow<N> gradient;
};

/// "mid": t_N = ε_N min(g_m, 0) (5.1) at x_m; ∂x_m/∂x_{n+1} = ½.
template <int N>
NormalTraction<N> midpoint_normal_traction(double eps, double g_m, const ElementVector<N>& Ns_m) {
  if (!(g_m < 0)) return {0, element_zero<ElementRow<N>>(Ns_m.size())};
  return {eps * g_m, 0.5 * eps * Ns_m.transpose()};  // (5.1)
}

/// "dd": t_N = (W_N(g_1) − W_N(g_n)) / (g_1 − g_n) (§5.2 item 2), in cancellation-free form.
template <int N>
NormalTraction<N> discrete_derivative_normal_traction(double eps, double g_n, double g_m, double g_1,
                                                      const ElementVector<N>& Ns_m,
                                                      const ElementVector<N>& Ns_1, double size) {
  if (!(g_n < 0 || g_1 < 0)) return {0, element_zero<ElementRow<N>>(Ns_m.size())};
  if (g_n <= 0 && g_1 <= 0) return {0.5 * eps * (g_n + g_1), 0.5 * eps * Ns_1.transpose()};  // = quotient
  const double dg = g_1 - g_n;
  if (std::abs(dg) < degenerate_gap_step * size) return midpoint_normal_traction<N>(eps, g_m, Ns_m);
  const double t = (normal_penalty_energy(eps, g_1) - normal_penalty_energy(eps, g_n)) / dg;  // §5.2 item 2
  const double dt_dg1 = (eps * std::min(g_1, 0.0) - t) / dg;  // ∂/∂g_{n+1}
  return {t, dt_dg1 * Ns_1.transpose()};                      // ∂g_1 = N_s(x_1)
}

/// Static steps: t_N = ε_N min(g_{n+1}, 0) at x_{n+1} (5b.7c).
template <int N>
NormalTraction<N> end_normal_traction(double eps, double g_1, const ElementVector<N>& Ns_1) {
  if (!(g_1 < 0)) return {0, element_zero<ElementRow<N>>(Ns_1.size())};
  return {eps * g_1, eps * Ns_1.transpose()};  // (5.1)
}

/// t_N of the pair's normal rule for the CPPs at x_n, x_m, x_{n+1} (gaps shifted by the kept offset).
template <int N>
NormalTraction<N> normal_traction(const PenaltyParameters& p, const Projection& at_n, const Projection& at_m,
                                  const Projection& at_1, const ElementVector<N>& Ns_m,
                                  const ElementVector<N>& Ns_1, double size) {
  if (p.at_end) return end_normal_traction<N>(p.normal_stiffness, at_1.gap - p.gap_offset, Ns_1);
  if (p.normal_rule == NormalRule::midpoint)
    return midpoint_normal_traction<N>(p.normal_stiffness, at_m.gap - p.gap_offset, Ns_m);
  return discrete_derivative_normal_traction<N>(p.normal_stiffness, at_n.gap - p.gap_offset,
                                                at_m.gap - p.gap_offset, at_1.gap - p.gap_offset, Ns_m, Ns_1,
                                                size);
}

/// ∂m_αβ/∂x = τ_α·∂τ_β + τ_β·∂τ_α (3.3), (3.8).
template <int N>
MetricGradient<N> metric_gradient(const SegmentFrame& f, const std::array<ElementRows3<N>, 2>& dtau) {
  MetricGradient<N> dm;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) dm[a][b] = f.tau(a).transpose() * dtau[b] + f.tau(b).transpose() * dtau[a];
  return dm;
}

/// Trial state and return map (5.3) with the derivative of t_{n+1} w.r.t. x_{n+1}.
template <int N>
struct TangentialTraction {
  bool slip = false;
  Eigen::Vector2d transported = Eigen::Vector2d::Zero();  ///< t̃_{n,α}
  Eigen::Vector2d value = Eigen::Vector2d::Zero();        ///< t_{n+1,α}
  Eigen::Vector2d slip_increment = Eigen::Vector2d::Zero();
  ElementRows2<N> gradient;
};

/// Gradients w.r.t. x_{n+1} at the evaluation point x_θ: θ ∂/∂x_θ, θ = evaluation_weight (½ at x_m).
template <int N>
struct PointGradients {
  std::array<ElementRows3<N>, 2> dtau;  ///< θ ∂τ_α/∂x_θ (3.8)
  MetricGradient<N> dm;                 ///< θ ∂m_αβ/∂x_θ
};

template <int N>
PointGradients<N> point_gradients(const SegmentFrame& frame, const std::array<ElementRows3<N>, 2>& dtau,
                                  double theta) {
  PointGradients<N> g{{theta * dtau[0], theta * dtau[1]}, metric_gradient<N>(frame, dtau)};
  for (auto& row : g.dm)
    for (ElementRow<N>& entry : row) entry *= theta;
  return g;
}

/// Inputs of the return map: the frame at the evaluation point (x_m, or x_{n+1} in static steps) with its
/// gradients w.r.t. x_{n+1}, D(x_{n+1}) and Δξ.
template <int N>
struct TangentialKinematics {
  const SegmentFrame& mid;
  const PointGradients<N>& at_point;  ///< point_gradients at the frame's configuration
  const ElementRows2<N>& D_1;         ///< ∂ξ_{n+1}/∂x_{n+1}
  Eigen::Vector2d dxi;                ///< Δξ = ξ_{n+1} − ξ_n
};

template <int N>
TangentialTraction<N> return_map(const TangentialKinematics<N>& k, const Eigen::Vector3d& history,
                                 const NormalTraction<N>& normal, const PenaltyParameters& p) {
  TangentialTraction<N> out;
  out.gradient = element_zero<ElementRows2<N>>(k.D_1.cols());
  const double eps = p.tangential_stiffness;
  if (!(eps > 0)) return out;
  const Eigen::Matrix2d& m = k.mid.metric;
  const auto& dtau = k.at_point.dtau;
  const auto& dm = k.at_point.dm;
  ElementRows2<N> dtr = element_zero<ElementRows2<N>>(k.D_1.cols());
  for (int a = 0; a < 2; ++a) {
    out.transported[a] = history.dot(k.mid.tau(a));  // t̃_{n,α} = t_{T,n}·τ_α (§5.2 item 3)
    dtr.row(a) = history.transpose() * dtau[a] + eps * (dm[a][0] * k.dxi[0] + dm[a][1] * k.dxi[1]);
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
  ElementRow<N> q_dm_q = element_zero<ElementRow<N>>(k.D_1.cols());
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) q_dm_q += q[a] * q[b] * dm[a][b];
  const ElementRow<N> dnorm =
      (q.transpose() * dtr - 0.5 * q_dm_q) / norm;  // ∂‖t^tr‖, ∂m^{-1} = −m^{-1}∂m m^{-1}
  const ElementRow<N> dpressure = -normal.gradient;
  out.gradient = (p.friction / norm) * trial * dpressure + scale * (dtr - trial * dnorm / norm);  // ∂(5.3)
  return out;
}

/// The variations of §3.3 a closed step needs at its evaluation point x_θ, whatever the surface.
template <int N>
struct PointVariations {
  const ElementVector<N>& Ns;   ///< (3.6)
  const ElementMatrix<N>& dNs;  ///< (3.9)
  const ElementRows2<N>& D;     ///< (3.7)
  double weight = 0.5;          ///< θ = ∂x_θ/∂x_{n+1} (evaluation_weight)
};

/// Fills a closed step: tractions, force (5.2) at x_θ, its tangent w.r.t. x_{n+1} given
/// xi_hessian = Σ_α t_α ∂D_α/∂x_θ at t = t_{n+1}, the new history and the energies (§5.2 items 5–7).
template <int N>
void fill_closed_step(PenaltyResultT<N>& out, const PointVariations<N>& mid,
                      const ElementMatrix<N>& xi_hessian, const NormalTraction<N>& normal,
                      const TangentialTraction<N>& tangential, const PenaltyParameters& p) {
  const SegmentFrame& f = out.at_m.frame;
  out.closed = true;
  out.slip = tangential.slip;
  out.normal_traction = normal.value;
  out.traction = tangential.value;  // t_alg = t_{n+1} (§5.2 item 5)
  out.transported_traction = tangential.transported;
  out.slip_increment = tangential.slip_increment;
  out.force = normal.value * mid.Ns + mid.D.transpose() * tangential.value;     // (5.2)
  out.tangent = mid.Ns * normal.gradient + mid.weight * normal.value * mid.dNs  // ∂(t_N N_s), (3.9)
                + mid.D.transpose() * tangential.gradient                       // ∂t_α D_α
                + mid.weight * xi_hessian;                                      // t_α ∂D_α
  const Eigen::Vector2d contravariant = f.metric_inv * tangential.value;
  out.history_after.traction = contravariant[0] * f.tau1 + contravariant[1] * f.tau2;          // §5.2 item 7
  out.normal_energy = normal_penalty_energy(p.normal_stiffness, out.at_1.gap - p.gap_offset);  // (5.1)
  out.tangential_energy = tangential_penalty_energy(tangential.value, f.metric_inv, p.tangential_stiffness);
  out.slip_work = tangential.slip ? tangential.value.dot(tangential.slip_increment) : 0.0;  // §5.2 item 7
}

/// The result of a step that stays open: W_N(g_{n+1}) only (5.1).
template <int N>
PenaltyResultT<N> open_result(PenaltyResultT<N> out, const PenaltyParameters& p) {
  if (out.at_1.converged)
    out.normal_energy = normal_penalty_energy(p.normal_stiffness, out.at_1.gap - p.gap_offset);
  return out;
}

}  // namespace penalty_law
}  // namespace stoss::contact
