#include "core/fem/neo_hookean.hpp"

#include <Eigen/LU>
#include <cmath>
#include <limits>

namespace stoss::fem {
namespace {

Eigen::Matrix3d right_cauchy_green(const Eigen::Matrix3d& E) {
  return 2 * E + Eigen::Matrix3d::Identity();
}

/// Ḡ = (cof C_a + 4 cof C_m + cof C_b)/6: Simpson's rule, exact for the quadratic cof, so that
/// det C_b − det C_a = Ḡ : (C_b − C_a) (2.15).
Eigen::Matrix3d mean_cofactor(const Eigen::Matrix3d& C_a, const Eigen::Matrix3d& C_b) {
  return (cofactor(C_a) + 4 * cofactor(0.5 * (C_a + C_b)) + cofactor(C_b)) / 6;
}

}  // namespace

Eigen::Matrix3d cofactor(const Eigen::Matrix3d& C) {
  const double I1 = C.trace(), I2 = 0.5 * (I1 * I1 - (C * C).trace());
  return C * C - I1 * C + I2 * Eigen::Matrix3d::Identity();  // Cayley–Hamilton
}

Eigen::Matrix3d cofactor_derivative(const Eigen::Matrix3d& C, const Eigen::Matrix3d& A) {
  const double trC = C.trace(), trA = A.trace();
  return C * A + A * C - trA * C - trC * A + (trC * trA - (C * A).trace()) * Eigen::Matrix3d::Identity();
}

NeoHookean::NeoHookean(double E, double nu) : lame_(Lame::from(E, nu)) {}

double NeoHookean::energy_density(const Eigen::Matrix3d& E) const {
  const Eigen::Matrix3d C = right_cauchy_green(E);
  const double I3 = C.determinant();
  if (!(I3 > 0)) return std::numeric_limits<double>::quiet_NaN();
  const double lnJ = 0.5 * std::log(I3);
  return 0.5 * lame_.mu * (C.trace() - 3) - lame_.mu * lnJ + 0.5 * lame_.lambda * lnJ * lnJ;  // (2.14)
}

Eigen::Matrix3d NeoHookean::evaluate_stress(const Eigen::Matrix3d& E, Matrix6d* tangent) const {
  const Eigen::Matrix3d C = right_cauchy_green(E), C_inv = C.inverse();
  const double lnJ = 0.5 * std::log(C.determinant());
  if (tangent) {
    const double shear = 2 * (lame_.mu - lame_.lambda * lnJ);
    *tangent = voigt_matrix([&](const Eigen::Matrix3d& dE) -> Eigen::Matrix3d {
      return shear * C_inv * dE * C_inv + lame_.lambda * (C_inv.cwiseProduct(dE)).sum() * C_inv;  // δS (2.14)
    });
  }
  return lame_.mu * (Eigen::Matrix3d::Identity() - C_inv) + lame_.lambda * lnJ * C_inv;  // (2.14)
}

NeoHookean::VolumetricQuotient NeoHookean::volumetric_quotient(double a, double b) const {
  // w(b) − w(a) = (L_b − L_a)(−μ/2 + λ/8 (L_a + L_b)), L = ln I₃, L_b − L_a = log1p((b − a)/a): no
  // cancellation, so the quotient stays accurate as b → a (the rigid motions of a step).
  const double delta = b - a, x = delta / a;
  const double L_a = std::log(a), L_b = std::log(b);
  const double log_quotient = x == 0 ? 1 / a : std::log1p(x) / delta;  // (L_b − L_a)/(b − a)
  const double s = -0.5 * lame_.mu + 0.125 * lame_.lambda * (L_a + L_b);
  // ∂/∂b of (L_b − L_a)/(b − a): (1/b − quotient)/(b − a), by its series where that would cancel.
  const double dq_db = std::abs(x) < 1e-5 ? (-0.5 + 2 * x / 3) / (a * a) : (1 / b - log_quotient) / delta;
  return {log_quotient * s, dq_db * s + log_quotient * 0.125 * lame_.lambda / b};
}

Eigen::Matrix3d NeoHookean::evaluate_discrete_stress(const Eigen::Matrix3d& E_a, const Eigen::Matrix3d& E_b,
                                                     Matrix6d* tangent) const {
  const Eigen::Matrix3d C_a = right_cauchy_green(E_a), C_b = right_cauchy_green(E_b);
  const Eigen::Matrix3d G = mean_cofactor(C_a, C_b);
  const VolumetricQuotient w = volumetric_quotient(C_a.determinant(), C_b.determinant());
  if (tangent) {
    const Eigen::Matrix3d C_m = 0.5 * (C_a + C_b), cof_b = cofactor(C_b);
    *tangent = voigt_matrix([&](const Eigen::Matrix3d& dE) -> Eigen::Matrix3d {
      const Eigen::Matrix3d dC = 2 * dE;  // δC_b; δC_m = ½ δC_b
      const double dI3 = cof_b.cwiseProduct(dC).sum();
      const Eigen::Matrix3d dG = (2 * cofactor_derivative(C_m, dC) + cofactor_derivative(C_b, dC)) / 6;
      return 2 * w.derivative_b * dI3 * G + 2 * w.value * dG;  // δ of (2.15)
    });
  }
  return lame_.mu * Eigen::Matrix3d::Identity() + 2 * w.value * G;  // (2.15)
}

}  // namespace stoss::fem
