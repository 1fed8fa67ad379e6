#pragma once
/// @file The weighted gaps of one slave face against one master face with their first and second
/// derivatives (docs/theory.md §4.7, (4.80) and (4.81)): what the mortar contact term needs for its residual
/// and its tangent.

#include <Eigen/Core>
#include <array>

#include "core/contact/mortar/mortar_integrals.hpp"

namespace stoss::contact::mortar {

using Matrix24 = Eigen::Matrix<double, 24, 24>;

/// g̃_j, D_jj and ∂g̃_j/∂x of one face pair; coordinates: slave nodes 1–4 then master nodes 1–4, 3 each.
struct PairGaps {
  Eigen::Vector4d gap = Eigen::Vector4d::Zero();             ///< g̃_j (4.79)
  Eigen::Vector4d weight = Eigen::Vector4d::Zero();          ///< D_jj of this pair (4.78)
  Eigen::Vector4d basis_integral = Eigen::Vector4d::Zero();  ///< ∫ Φ_j ψ dA over the overlap
  Eigen::Matrix<double, 4, 24> gradient = Eigen::Matrix<double, 4, 24>::Zero();  ///< ∂g̃_j/∂x (4.80)
  double area = 0;                                                               ///< the clip polygon's area
  double facing_weight = 0;                                                      ///< ψ of (4.76)
};

/// The gaps and their gradient, by forward dual numbers (4.80). `offset`: the nodes' frozen nodal gaps c_j,
/// g̃_j = ∫ Φ_j (g − c_j) (4.83).
PairGaps pair_gaps(const SegmentNodes& slave, const SegmentNodes& master, Multipliers kind,
                   const Eigen::Vector4d& offset = Eigen::Vector4d::Zero());

/// The gaps, their gradient and Σ_j λ_j ∂²g̃_j/∂x² (4.81), by second-order forward numbers (second_order.hpp).
PairGaps pair_gaps(const SegmentNodes& slave, const SegmentNodes& master, Multipliers kind,
                   const Eigen::Vector4d& lambda, Matrix24& weighted_hessian,
                   const Eigen::Vector4d& offset = Eigen::Vector4d::Zero());

}  // namespace stoss::contact::mortar
