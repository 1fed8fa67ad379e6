#pragma once
/// @file St. Venant–Kirchhoff: W(E) = ½ λ (tr E)² + μ E:E (docs/theory.md (1.4)). Quadratic in E, so the
/// average stress is its exact discrete stress (2.6). Softens and can collapse under strong compression.

#include "core/fem/material.hpp"

namespace stoss::fem {

class SaintVenantKirchhoff final : public Material {
 public:
  SaintVenantKirchhoff(double youngs_modulus, double poisson_ratio);
  std::string name() const override { return "saint_venant_kirchhoff"; }
  double lambda() const { return lame_.lambda; }
  double mu() const { return lame_.mu; }

  double energy_density(const Eigen::Matrix3d& E) const override;
  /// S = λ tr E 1 + 2μ E; the tangent is constant: λ 1⊗1 + 2μ 𝕀.
  Eigen::Matrix3d evaluate_stress(const Eigen::Matrix3d& E, Matrix6d* tangent) const override;
  /// ½ (S(E_a) + S(E_b)) (2.6), tangent ½ (λ 1⊗1 + 2μ 𝕀).
  Eigen::Matrix3d evaluate_discrete_stress(const Eigen::Matrix3d& E_a, const Eigen::Matrix3d& E_b,
                                           Matrix6d* tangent) const override;

 private:
  Lame lame_;
  Matrix6d tangent_;
};

}  // namespace stoss::fem
