#pragma once
/// @file Compressible neo-Hookean material (docs/theory.md §1.2, §2.6):
///   W = μ/2 (I₁ − 3) − μ ln J + λ/2 (ln J)²,   I₁ = tr C, J² = I₃ = det C,
/// with the Lamé parameters of (1.5), so that it agrees with St. Venant–Kirchhoff for small strains.
/// W → ∞ as J → 0: an element cannot be compressed to zero volume. The energy–momentum stress is the
/// discrete gradient in the invariants I₁ and I₃ (2.15), exact for this non-quadratic energy.

#include "core/fem/material.hpp"

namespace stoss::fem {

class NeoHookean final : public Material {
 public:
  NeoHookean(double youngs_modulus, double poisson_ratio);
  std::string name() const override { return "neo_hookean"; }

  /// NaN when det C ≤ 0 (an inverted point has no energy; Newton backtracks from it).
  double energy_density(const Eigen::Matrix3d& E) const override;
  /// S = μ (1 − C⁻¹) + λ ln J C⁻¹ (2.14), and its δS.
  Eigen::Matrix3d evaluate_stress(const Eigen::Matrix3d& E, Matrix6d* tangent) const override;
  /// S_alg = μ 1 + 2 w̄′ Ḡ (2.15), and δ of (2.15).
  Eigen::Matrix3d evaluate_discrete_stress(const Eigen::Matrix3d& E_a, const Eigen::Matrix3d& E_b,
                                           Matrix6d* tangent) const override;

 private:
  /// The volumetric part w(I₃) = −μ/2 ln I₃ + λ/8 (ln I₃)² and its divided difference w̄′ between I₃ᵃ, I₃ᵇ,
  /// with ∂w̄′/∂I₃ᵇ.
  struct VolumetricQuotient {
    double value, derivative_b;
  };
  VolumetricQuotient volumetric_quotient(double I3_a, double I3_b) const;
  Lame lame_;
};

/// cof C = det(C) C⁻ᵀ, for symmetric C: C² − I₁ C + I₂ 1.
Eigen::Matrix3d cofactor(const Eigen::Matrix3d& C);
/// The derivative of cof at C in direction A (C, A symmetric).
Eigen::Matrix3d cofactor_derivative(const Eigen::Matrix3d& C, const Eigen::Matrix3d& A);

}  // namespace stoss::fem
