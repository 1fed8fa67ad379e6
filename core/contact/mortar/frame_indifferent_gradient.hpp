#pragma once
/// @file The energy–momentum form of mortar contact (docs/theory.md §4.7.2, (4.85)–(4.88)): a discrete
/// gradient of one face pair's weighted gaps between x_n and x_{n+1} that is exact for the gaps' increments
/// and exerts no net force or moment about the midpoint configuration.

#include <Eigen/Core>

#include "core/contact/mortar/pair_derivatives.hpp"

namespace stoss::contact::mortar {

using Vector24 = Eigen::Matrix<double, 24, 1>;

/// The part w of a face pair's step Δ = x_{n+1} − x_n that no rigid motion of its midpoint configuration
/// makes (4.85), and ∂w/∂x_{n+1} (4.86). Coordinates as PairGaps': slave nodes then master nodes, 3 each.
struct StepDeformation {
  Vector24 w = Vector24::Zero();
  Matrix24 derivative = Matrix24::Zero();
};
StepDeformation step_deformation(const Vector24& x_n, const Vector24& x_1);

/// The discrete gradients G_j of the four weighted gaps (4.87) and ∂(Σ_j λ_j G_j)/∂x_{n+1} (4.88).
struct PairDiscreteGradient {
  Eigen::Matrix<double, 4, 24> gradient = Eigen::Matrix<double, 4, 24>::Zero();  ///< G_j
  Matrix24 tangent = Matrix24::Zero();  ///< filled when a weighted Hessian was given
};

/// What (4.87) is built from: the pair's coordinates at both ends, its gaps at x_n, its gaps with their
/// gradient at x_{n+1} and at the midpoint, and (for the tangent) Σ_j λ_j ∂²g̃_j/∂x² at the midpoint.
/// `length` scales the threshold under which the step counts as rigid (then G_j = ∂g̃_j/∂x at the midpoint).
struct PairStep {
  const Vector24& x_n;
  const Vector24& x_1;
  const Eigen::Vector4d& gap_n;
  const PairGaps& at_end;
  const PairGaps& at_midpoint;
  const Matrix24* weighted_hessian = nullptr;  ///< at the midpoint; null: no tangent
  double length = 1;
};
PairDiscreteGradient discrete_gradient(const PairStep& step, const Eigen::Vector4d& lambda);

}  // namespace stoss::contact::mortar
