#pragma once
/// @file Bilinear 4-node master segment: shape functions and the local frame at a point ξ
/// (docs/theory.md §3.1, (3.1)–(3.3)).

#include <Eigen/Core>

#include "core/contact/types.hpp"

namespace stoss::contact {

/// Bilinear shape functions at ξ (3.1). Corners K = 1…4 (rows 0–3) sit at (−1,−1), (1,−1), (1,1),
/// (−1,1). `N_{K,11} = N_{K,22} = 0`, so `d2N12` is the only second derivative.
struct BilinearShape {
  Eigen::Vector4d N;               ///< N_K
  Eigen::Matrix<double, 4, 2> dN;  ///< N_{K,α} (column α)
  Eigen::Vector4d d2N12;           ///< N_{K,12} (constant)
};
BilinearShape bilinear_shape(const Eigen::Vector2d& xi);

/// Geometry of a master segment at the convective coordinates ξ.
/// @note `normal` = τ_1 × τ_2 / |τ_1 × τ_2| points out of the master body for nodes in the outward
///       order of §1.1. For a degenerate segment (τ_1 × τ_2 = 0) `normal` is zero and, if the metric
///       is singular, `metric_inv` is zero too; nothing is NaN.
struct SegmentFrame {
  Eigen::Vector2d xi;
  Eigen::Vector3d y;           ///< y(ξ) = Σ N_K y_K (3.2)
  Eigen::Vector3d tau1;        ///< τ_1 = y_{,1}
  Eigen::Vector3d tau2;        ///< τ_2 = y_{,2}
  Eigen::Vector3d y12;         ///< y_{,12}
  Eigen::Vector3d normal;      ///< n (3.3)
  Eigen::Matrix2d metric;      ///< m_αβ = τ_α·τ_β
  Eigen::Matrix2d metric_inv;  ///< m^{αβ}
  Eigen::Vector4d N;
  Eigen::Matrix<double, 4, 2> dN;
  Eigen::Vector4d d2N12;

  /// τ_α for α = 0, 1.
  const Eigen::Vector3d& tau(int alpha) const { return alpha == 0 ? tau1 : tau2; }
};

/// Evaluates the frame of the segment with nodes y_1 … y_4 (rows of `nodes`) at ξ.
SegmentFrame segment_frame(const SegmentNodes& nodes, const Eigen::Vector2d& xi);

}  // namespace stoss::contact
