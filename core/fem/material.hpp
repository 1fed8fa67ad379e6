#pragma once
/// @file Hyperelastic materials in the Green–Lagrange strain E: energy density, stress, tangent, and the
/// discrete stress of the energy–momentum scheme.

#include <Eigen/Core>

namespace stoss::fem {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// Voigt order [11, 22, 33, 23, 13, 12], engineering shear strains.
Eigen::Matrix<double, 6, 1> to_voigt_stress(const Eigen::Matrix3d& S);

/// St. Venant–Kirchhoff: W(E) = ½ λ (tr E)² + μ E:E (docs/theory.md (1.4)).
class SaintVenantKirchhoff {
 public:
  SaintVenantKirchhoff(double youngs_modulus, double poisson_ratio);
  double lambda() const { return lambda_; }
  double mu() const { return mu_; }

  double energy_density(const Eigen::Matrix3d& E) const;
  /// Second Piola–Kirchhoff stress S = ∂W/∂E.
  Eigen::Matrix3d stress(const Eigen::Matrix3d& E) const;
  /// ∂S/∂E in Voigt form (constant for this material).
  const Matrix6d& tangent() const { return tangent_; }
  /// Stress S_alg with W(E_b) − W(E_a) = S_alg : (E_b − E_a) exactly (2.6); for SVK the average.
  Eigen::Matrix3d discrete_stress(const Eigen::Matrix3d& E_a, const Eigen::Matrix3d& E_b) const;
  /// ∂S_alg/∂E_b in Voigt form.
  Matrix6d discrete_stress_tangent() const { return 0.5 * tangent_; }

 private:
  double lambda_, mu_;
  Matrix6d tangent_;
};

}  // namespace stoss::fem
