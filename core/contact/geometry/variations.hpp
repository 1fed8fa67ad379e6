#pragma once
/// @file First variations of the NTS gap at the closest point, and the derivative of the gap
/// gradient (docs/theory.md §3.3, (3.6)–(3.9)).
///
/// All derivatives are with respect to the element vector x = [x_s; y_1; y_2; y_3; y_4] (15
/// entries, node K of the segment at entries 3 + 3K). They hold at a converged CPP (§3.2): pass the
/// `frame` and `gap` of a converged `Projection`.

#include <Eigen/Core>
#include <array>

#include "core/contact/geometry/segment.hpp"
#include "core/contact/types.hpp"

namespace stoss::contact {

/// N_s = ∂g_N/∂x = [n; −N_1 n; …; −N_4 n] (3.6).
Vector15 gap_gradient(const SegmentFrame& frame);

/// T_α = [τ_α; −N_1 τ_α; …; −N_4 τ_α] as rows α (3.7).
Matrix2x15 tangent_variation(const SegmentFrame& frame);

/// N̄_α = [0; N_{1,α} n; …; N_{4,α} n] as rows α (3.7).
Matrix2x15 normal_variation(const SegmentFrame& frame);

/// D_α = ∂ξ^α/∂x = A^{αβ} (T_β + g_N N̄_β) as rows α (3.7), with A of (3.4) at the CPP.
Matrix2x15 xi_gradient(const SegmentFrame& frame, double gap);

/// ∂τ_α/∂x = [0; N_{1,α} 1; …; N_{4,α} 1] + y_{,12} ⊗ D_β (β ≠ α) (3.8), for α = 0, 1.
std::array<Matrix3x15, 2> tangent_gradients(const SegmentFrame& frame, const Matrix2x15& D);

/// ∂n/∂x = −m^{αβ} τ_β ⊗ (n·∂τ_α/∂x) (3.8).
Matrix3x15 normal_gradient(const SegmentFrame& frame, const std::array<Matrix3x15, 2>& dtau);

/// ∂N_s/∂x = [∂n/∂x; −n ⊗ (N_{K,α} D_α) − N_K ∂n/∂x (K = 1…4)] (3.9): the Hessian of g_N,
/// symmetric up to round-off; the midpoint-NTS Lagrange tangent of §4.2.
Matrix15 gap_hessian(const SegmentFrame& frame, const Matrix2x15& D, const Matrix3x15& dn);

/// Everything of §3.3 at one CPP.
struct GapVariations {
  Vector15 Ns;                     ///< (3.6)
  Matrix2x15 D;                    ///< (3.7)
  std::array<Matrix3x15, 2> dtau;  ///< (3.8)
  Matrix3x15 dn;                   ///< (3.8)
  Matrix15 dNs;                    ///< (3.9)
};
GapVariations gap_variations(const SegmentFrame& frame, double gap);

}  // namespace stoss::contact
