#pragma once
/// @file Gonzalez discrete gradient of the constraints g(π) with the cancellation-free defect, and
/// its derivative with respect to π at t_{n+1} (docs/theory.md §4.3.6, (4.6)–(4.8)).

#include <Eigen/Core>
#include <array>

#include "core/contact/types.hpp"

namespace stoss::contact {

/// c_k = g_k(π_b) − g_k(π_a) − ∇g_k(π_m)·δ in closed form (4.7), from π_m = (π_a + π_b)/2 and
/// δ = π_b − π_a: ¼ of the t³ coefficient of g_k(π_m + tδ). No subtraction of nearly equal values,
/// so it is accurate for any |δ|.
Vector6 discrete_gradient_defect(const Vector17& pi_m, const Vector17& delta);

/// ∇̄g and ∂∇̄g_k/∂π_b.
struct DiscreteGradient {
  Matrix6x17 value;                    ///< ∇̄g (4.6); g(π_b) − g(π_a) = ∇̄g δ
  std::array<Matrix17, 6> derivative;  ///< (i, j) = ∂(∇̄g_k)_i/∂(π_b)_j (4.8)
};

/// ∇̄g_k = ∇g_k(π_m) + c_k δᵀ/|δ|² (4.6) and its derivative (4.8); for δ = 0 (|δ|² = 0 in floating
/// point) ∇g(π_m) and ½H_k(π_m). Finite for every finite input: |δ|⁴ is never formed.
DiscreteGradient discrete_gradient(const Vector17& pi_a, const Vector17& pi_b);

}  // namespace stoss::contact
