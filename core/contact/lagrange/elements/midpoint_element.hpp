#pragma once
/// @file Residual and tangent of one active NTS Lagrange element of the implicit midpoint rule
/// (docs/theory.md §4.2, (4.2)).

#include <Eigen/Core>

#include "core/contact/geometry/projection.hpp"
#include "core/contact/types.hpp"

namespace stoss::contact {

/// One element's contributions at the current iterate; element vectors are [x_s; y_1 … y_4].
/// @note `Rx` adds to R_x of (4.2); the derivatives are with respect to x_{n+1} and λ. If either CPP
///       failed (`converged` false) the blocks are evaluated at the last iterate and must not be used.
struct MidpointResult {
  bool converged = false;  ///< both CPPs (at x_m and at x_{n+1}) converged
  Vector15 Rx;             ///< h λ N_s(x_m) (4.2)
  double Rl = 0;           ///< g_N(x_{n+1}) − f_3 (4.2)
  Matrix15 Kxx;            ///< (h/2) λ ∂N_s/∂x(x_m) (3.9)
  Vector15 Kxl;            ///< h N_s(x_m)
  RowVector15 Klx;         ///< N_s(x_{n+1})ᵀ
  Projection mid;          ///< CPP of x_m
  Projection end;          ///< CPP of x_{n+1}
};

/// The element at (x_n, x_{n+1}) with multiplier λ, gap target f_3 and step h; both CPPs start from
/// `xi_start`.
MidpointResult midpoint_element(const Vector15& x_n, const Vector15& x_1, double lambda, double f3, double h,
                                const Eigen::Vector2d& xi_start);

}  // namespace stoss::contact
