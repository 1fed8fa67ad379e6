#pragma once
/// @file Closest-point projection (CPP) of a slave node onto a bilinear master segment and the
/// normal gap (docs/theory.md §3.2, (3.4)–(3.5)).

#include <Eigen/Core>

#include "core/contact/geometry/segment.hpp"
#include "core/contact/types.hpp"

namespace stoss::contact {

/// Stop rules of the CPP Newton iteration (§3.2).
struct ProjectionLimits {
  static constexpr double step_tolerance = 1e-13;        ///< converged when |Δξ| < this
  static constexpr double stagnation_tolerance = 1e-11;  ///< … or < this after ≥ 3 iterations
  static constexpr int stagnation_iterations = 3;
  static constexpr double max_xi = 10;  ///< "no projection" when |ξ|_∞ exceeds this
  static constexpr int max_iterations = 30;
};

/// Outcome of a closest-point projection.
/// @note On success `xi` is the CPP, `frame` is evaluated there and `gap` = g_N (3.5): positive
///       open, negative penetrating. On failure ("no projection": |ξ|_∞ > 10, det A ≤ 0, or 30
///       iterations) `xi` is the last iterate with |ξ|_∞ ≤ 10 (or the start), and `frame`, `gap` are
///       evaluated there — finite, but not a projection.
struct Projection {
  bool converged = false;
  Eigen::Vector2d xi = Eigen::Vector2d::Zero();
  double gap = 0;
  SegmentFrame frame;
  int iterations = 0;  ///< Newton updates performed
};

/// The stop rule of §3.2 for a CPP Newton update of length `step` in iteration `iteration` (1-based).
bool converged_step(double step, int iteration);

/// r_α = (x_s − y(ξ))·τ_α(ξ), the CPP residual (seed eq. 10), for r = x_s − y(ξ).
Eigen::Vector2d projection_residual(const SegmentFrame& frame, const Eigen::Vector3d& r);

/// A_αβ = m_αβ − r·y_{,αβ} (3.4), for r = x_s − y(ξ); at the CPP r = g_N n.
Eigen::Matrix2d projection_matrix(const SegmentFrame& frame, const Eigen::Vector3d& r);

/// Newton iteration ξ ← ξ + A^{-1} r (3.4) from `xi_start` (the previous ξ, else 0) with the stop
/// rules of §3.2, then g_N = (x_s − y(ξ))·n (3.5).
Projection closest_point_projection(const Eigen::Vector3d& slave, const SegmentNodes& nodes,
                                    const Eigen::Vector2d& xi_start = Eigen::Vector2d::Zero());

/// True if ξ ∈ [−1−eps, 1+eps]² (acceptance test of §3.4, eps = ε_ξ).
bool inside(const Eigen::Vector2d& xi, double eps);

}  // namespace stoss::contact
