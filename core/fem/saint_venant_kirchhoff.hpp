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
  Eigen::Matrix3d stress(const Eigen::Matrix3d& E) const override;
  /// Constant: λ 1⊗1 + 2μ 𝕀.
  Matrix6d tangent(const Eigen::Matrix3d&) const override { return tangent_; }
  /// ½ (S(E_a) + S(E_b)) (2.6).
  Eigen::Matrix3d discrete_stress(const Eigen::Matrix3d& E_a, const Eigen::Matrix3d& E_b) const override;
  Matrix6d discrete_stress_tangent(const Eigen::Matrix3d&, const Eigen::Matrix3d&) const override {
    return 0.5 * tangent_;
  }

 private:
  Lame lame_;
  Matrix6d tangent_;
};

}  // namespace stoss::fem
