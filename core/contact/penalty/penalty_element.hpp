#pragma once
/// @file Frictional penalty contact of one NTS element: one slave node against one 4-node master
/// segment over one time step n → n+1 (docs/theory.md §5, (5.1)–(5.4)).
///
/// Pure functions: the friction history goes in, the updated history comes out (`history_after`),
/// to be committed by the caller only when the step has converged (§5.2 item 7). The master face is
/// the one assigned for the step (§3.4); this element does not test whether ξ lies on the face.
///
/// Tangent: analytic (no finite differences). ∂D_α/∂x, the second derivative of the CPP that
/// (5.2) needs, is the derivative of (3.7) at fixed traction, built from (3.4), (3.8) and (3.9);
/// everything is fixed-size, no heap allocation. Checked against central differences in
/// tests/core/contact/test_penalty_element.cpp.

#include <Eigen/Core>

#include "core/contact/geometry/projection.hpp"
#include "core/contact/types.hpp"

namespace stoss::contact {

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
};

/// Friction history of one element: the spatial tangential traction t_{T,n} (§5.2 item 3).
/// Zero while the contact is open.
struct FrictionHistory {
  Eigen::Vector3d traction = Eigen::Vector3d::Zero();
};

/// One element over one step. Vectors are in the element order [x_s; y_1; y_2; y_3; y_4].
/// @note When the contact is open (or one of the three CPPs did not converge), `force`, `tangent`,
///       the tractions, `slip_increment`, `tangential_energy` and `slip_work` are zero and
///       `history_after` is reset (§5.2 item 7); `normal_energy` is still W_N(g_{n+1}) when the CPP
///       of x_{n+1} converged (e.g. nonzero for "mid" with g_m ≥ 0 > g_{n+1}).
struct PenaltyResult {
  bool closed = false;                  ///< contact closed in this step per the normal rule (§5.2 item 2)
  bool slip = false;                    ///< return map (5.3): slip (true) or stick
  Vector15 force = Vector15::Zero();    ///< t_N N_s(x_m) + t_{n+1,α} D_α(x_m) (5.2); caller multiplies by h
  Matrix15 tangent = Matrix15::Zero();  ///< ∂force/∂x_{n+1} (non-symmetric)
  double normal_traction = 0;           ///< t_N ≤ 0
  Eigen::Vector2d traction = Eigen::Vector2d::Zero();              ///< covariant t_{n+1,α} (5.3)
  Eigen::Vector2d transported_traction = Eigen::Vector2d::Zero();  ///< t̃_{n,α} = t_{T,n}·τ_α(x_m)
  Eigen::Vector2d slip_increment = Eigen::Vector2d::Zero();        ///< Δξ_p (contravariant) (5.3)
  double normal_energy = 0;                                        ///< W_N(g_{n+1}) (5.1)
  double tangential_energy = 0;  ///< W_T(t_{n+1}) = ‖t_{n+1}‖²/(2ε_T), metric at x_m (5.1)
  double slip_work = 0;  ///< t_{n+1}·Δξ_p = μ p ‖Δξ_p‖ ≥ 0; exactly 0 in stick (§5.2 item 7)
  FrictionHistory history_after;  ///< t_{T,n+1} = t_{n+1,α} m^{αβ} τ_β(x_m); commit after convergence
  Projection at_n, at_m, at_1;    ///< the CPPs of x_n, x_m = (x_n + x_{n+1})/2 and x_{n+1}
};

/// W_N(g) = ½ ε_N min(g, 0)² (5.1).
double normal_penalty_energy(double normal_stiffness, double gap);

/// W_T = ‖t‖²/(2ε_T), ‖t‖² = t_α m^{αβ} t_β (5.1), for covariant t and the inverse metric m^{αβ};
/// 0 when ε_T = 0.
double tangential_penalty_energy(const Eigen::Vector2d& traction, const Eigen::Matrix2d& metric_inv,
                                 double tangential_stiffness);

/// Default penalty stiffness ε_N = ε_T = 10 E ℓ [choice] (§5.1): E the Young's modulus, ℓ the mean
/// master face size; units of force/length. Check that penetration stays below 1 % of ℓ.
double penalty_default_stiffness(double youngs_modulus, double face_size);

/// The element of §5.2 for the step x_n → x_{n+1} with friction history `history`: CPPs at x_n,
/// x_m, x_{n+1} (all from `xi_start`), normal traction per `p.normal_rule`, history transport,
/// trial and return map (5.3), force (5.2) at x_m and its analytic tangent w.r.t. x_{n+1}.
PenaltyResult penalty_element(const Vector15& x_n, const Vector15& x_1, const FrictionHistory& history,
                              const PenaltyParameters& p, const Eigen::Vector2d& xi_start);

}  // namespace stoss::contact
