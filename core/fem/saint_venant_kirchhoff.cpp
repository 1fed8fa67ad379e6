#include "core/fem/saint_venant_kirchhoff.hpp"

namespace stoss::fem {

SaintVenantKirchhoff::SaintVenantKirchhoff(double E, double nu) : lame_(Lame::from(E, nu)) {
  tangent_.setZero();
  tangent_.topLeftCorner<3, 3>().setConstant(lame_.lambda);
  for (int i = 0; i < 3; ++i) {
    tangent_(i, i) += 2 * lame_.mu;
    tangent_(i + 3, i + 3) = lame_.mu;
  }
}

double SaintVenantKirchhoff::energy_density(const Eigen::Matrix3d& E) const {
  const double tr = E.trace();
  return 0.5 * lame_.lambda * tr * tr + lame_.mu * E.squaredNorm();  // (1.4)
}

Eigen::Matrix3d SaintVenantKirchhoff::evaluate_stress(const Eigen::Matrix3d& E, Matrix6d* tangent) const {
  if (tangent) *tangent = tangent_;
  return lame_.lambda * E.trace() * Eigen::Matrix3d::Identity() + 2 * lame_.mu * E;  // (1.4)
}

Eigen::Matrix3d SaintVenantKirchhoff::evaluate_discrete_stress(const Eigen::Matrix3d& E_a,
                                                               const Eigen::Matrix3d& E_b,
                                                               Matrix6d* tangent) const {
  if (tangent) *tangent = 0.5 * tangent_;
  return 0.5 * (stress(E_a) + stress(E_b));  // (2.6): exact for an energy quadratic in E
}

}  // namespace stoss::fem
