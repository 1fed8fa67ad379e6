#include "core/fem/material.hpp"

namespace stoss::fem {

Eigen::Matrix<double, 6, 1> to_voigt_stress(const Eigen::Matrix3d& S) {
  Eigen::Matrix<double, 6, 1> s;
  s << S(0, 0), S(1, 1), S(2, 2), S(1, 2), S(0, 2), S(0, 1);
  return s;
}

SaintVenantKirchhoff::SaintVenantKirchhoff(double E, double nu)
    : lambda_(E * nu / ((1 + nu) * (1 - 2 * nu))), mu_(E / (2 * (1 + nu))) {  // (1.5)
  tangent_.setZero();
  tangent_.topLeftCorner<3, 3>().setConstant(lambda_);
  for (int i = 0; i < 3; ++i) {
    tangent_(i, i) += 2 * mu_;
    tangent_(i + 3, i + 3) = mu_;
  }
}

double SaintVenantKirchhoff::energy_density(const Eigen::Matrix3d& E) const {
  const double tr = E.trace();
  return 0.5 * lambda_ * tr * tr + mu_ * E.squaredNorm();  // (1.4)
}

Eigen::Matrix3d SaintVenantKirchhoff::stress(const Eigen::Matrix3d& E) const {
  return lambda_ * E.trace() * Eigen::Matrix3d::Identity() + 2 * mu_ * E;  // (1.4)
}

Eigen::Matrix3d SaintVenantKirchhoff::discrete_stress(const Eigen::Matrix3d& E_a, const Eigen::Matrix3d& E_b) const {
  return 0.5 * (stress(E_a) + stress(E_b));  // (2.6): exact for an energy quadratic in E
}

}  // namespace stoss::fem
