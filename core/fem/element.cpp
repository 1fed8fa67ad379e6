#include "core/fem/element.hpp"

#include <Eigen/LU>
#include <cmath>

namespace stoss::fem {
namespace {

using Matrix6x24 = Eigen::Matrix<double, 6, 24>;

/// δE (Voigt, engineering shear) = B δx for the element's 24 dofs at deformation gradient F.
Matrix6x24 strain_displacement(const Eigen::Matrix3d& F, const Matrix83& dN_dX) {
  Matrix6x24 B;
  for (int I = 0; I < 8; ++I) {
    const Eigen::RowVector3d g = dN_dX.row(I);
    for (int k = 0; k < 3; ++k) {
      const int c = 3 * I + k;
      B(0, c) = F(k, 0) * g[0];
      B(1, c) = F(k, 1) * g[1];
      B(2, c) = F(k, 2) * g[2];
      B(3, c) = F(k, 1) * g[2] + F(k, 2) * g[1];
      B(4, c) = F(k, 0) * g[2] + F(k, 2) * g[0];
      B(5, c) = F(k, 0) * g[1] + F(k, 1) * g[0];
    }
  }
  return B;
}

/// Geometric stiffness (∇N_I · S ∇N_J) 1, the first term of (1.8).
void add_geometric_stiffness(const Matrix83& dN_dX, const Eigen::Matrix3d& S, double factor, Matrix24& K) {
  const Matrix8 G = factor * dN_dX * S * dN_dX.transpose();
  for (int I = 0; I < 8; ++I)
    for (int J = 0; J < 8; ++J)
      for (int k = 0; k < 3; ++k) K(3 * I + k, 3 * J + k) += G(I, J);
}

void add_nodal_force(const Matrix83& dN_dX, const Eigen::Matrix3d& S, const Eigen::Matrix3d& F, double wJ,
                     Vector24& f) {
  const Matrix83 fI = wJ * dN_dX * S * F.transpose();  // (1.6): row I = (F S ∇N_I)ᵀ
  for (int I = 0; I < 8; ++I) f.segment<3>(3 * I) += fI.row(I).transpose();
}

}  // namespace

Eigen::Matrix3d green_lagrange_strain(const Eigen::Matrix3d& F) {
  return 0.5 * (F.transpose() * F - Eigen::Matrix3d::Identity());
}

Eigen::Matrix3d deformation_gradient(const Matrix83& x, const GaussPoint& gp) {
  return x.transpose() * gp.dN_dX;  // (1.3)
}

double strain_energy(const ElementGeometry& e, const Material& m, const Matrix83& x) {
  double V = 0;
  for (const GaussPoint& gp : e.gp)
    V += gp.wJ * m.energy_density(green_lagrange_strain(deformation_gradient(x, gp)));
  return V;  // (1.7)
}

void internal_force(const ElementGeometry& e, const Material& m, const Matrix83& x, Vector24& f,
                    Matrix24* K) {
  f.setZero();
  if (K) K->setZero();
  for (const GaussPoint& gp : e.gp) {
    const Eigen::Matrix3d F = deformation_gradient(x, gp);
    const Eigen::Matrix3d E = green_lagrange_strain(F);
    Matrix6d D;
    const Eigen::Matrix3d S = m.evaluate_stress(E, K ? &D : nullptr);
    add_nodal_force(gp.dN_dX, S, F, gp.wJ, f);
    if (!K) continue;
    const Matrix6x24 B = strain_displacement(F, gp.dN_dX);
    K->noalias() += gp.wJ * B.transpose() * D * B;  // material part of (1.8)
    add_geometric_stiffness(gp.dN_dX, S, gp.wJ, *K);
  }
}

void discrete_gradient_force(const ElementGeometry& e, const Material& m, const Matrix83& x_n,
                             const Matrix83& x_1, Vector24& f, Matrix24* K) {
  f.setZero();
  if (K) K->setZero();
  const Matrix83 x_m = 0.5 * (x_n + x_1);
  for (const GaussPoint& gp : e.gp) {
    const Eigen::Matrix3d F_n = deformation_gradient(x_n, gp), F_1 = deformation_gradient(x_1, gp);
    const Eigen::Matrix3d F_m = deformation_gradient(x_m, gp);
    const Eigen::Matrix3d E_n = green_lagrange_strain(F_n), E_1 = green_lagrange_strain(F_1);
    Matrix6d D_alg;
    const Eigen::Matrix3d S_alg = m.evaluate_discrete_stress(E_n, E_1, K ? &D_alg : nullptr);
    add_nodal_force(gp.dN_dX, S_alg, F_m, gp.wJ, f);  // (2.6)
    if (!K) continue;
    const Matrix6x24 B_m = strain_displacement(F_m, gp.dN_dX), B_1 = strain_displacement(F_1, gp.dN_dX);
    K->noalias() += gp.wJ * B_m.transpose() * D_alg * B_1;      // (2.9), material part
    add_geometric_stiffness(gp.dN_dX, S_alg, 0.5 * gp.wJ, *K);  // (2.9), ½ ∂F_m/∂x_1
  }
}

Eigen::Matrix3d average_cauchy_stress(const ElementGeometry& e, const Material& m, const Matrix83& x) {
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  double volume = 0;
  for (const GaussPoint& gp : e.gp) {
    const Eigen::Matrix3d F = deformation_gradient(x, gp);
    const double J = F.determinant();
    const Eigen::Matrix3d S = m.stress(green_lagrange_strain(F));
    const double w = gp.wJ * J;  // the Gauss point's current volume
    sum += w * (F * S * F.transpose()) / J;
    volume += w;
  }
  return sum / volume;
}

double von_mises(const Eigen::Matrix3d& sigma) {
  const Eigen::Matrix3d s = sigma - sigma.trace() / 3 * Eigen::Matrix3d::Identity();
  return std::sqrt(1.5 * (s.array() * s.array()).sum());
}

Matrix8 consistent_mass(const ElementGeometry& e, double density) {
  Matrix8 M = Matrix8::Zero();
  for (const GaussPoint& gp : e.gp) M.noalias() += (gp.wJ * density) * gp.N * gp.N.transpose();  // (1.9)
  return M;
}

}  // namespace stoss::fem
