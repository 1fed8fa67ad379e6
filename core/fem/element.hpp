#pragma once
/// @file Hex8 total-Lagrangian element kernels: strain energy, internal force and tangent for each force
/// rule of the time schemes, and the consistent mass (docs/theory.md §1.3–1.4, §2).

#include <Eigen/Core>

#include "core/fem/hex8.hpp"
#include "core/fem/material.hpp"

namespace stoss::fem {

using Vector24 = Eigen::Matrix<double, 24, 1>;
using Matrix24 = Eigen::Matrix<double, 24, 24>;
using Matrix8 = Eigen::Matrix<double, 8, 8>;

/// Green–Lagrange strain E = ½ (FᵀF − 1).
Eigen::Matrix3d green_lagrange_strain(const Eigen::Matrix3d& F);

/// Deformation gradient F = Σ_I x_I ⊗ ∇_X N_I (1.3); x holds the element's nodes as rows.
Eigen::Matrix3d deformation_gradient(const Matrix83& x, const GaussPoint& gp);

/// V_e (1.7).
double strain_energy(const ElementGeometry& e, const Material& m, const Matrix83& x);

/// f_e (1.6) at x, and K_e = ∂f/∂x (1.8) if K is not null. Dof order 3I + i.
void internal_force(const ElementGeometry& e, const Material& m, const Matrix83& x, Vector24& f, Matrix24* K);

/// Energy–momentum force f̄ (2.6) for the step x_n → x_1, and K̄ = ∂f̄/∂x_1 (2.9) if K is not null.
void discrete_gradient_force(const ElementGeometry& e, const Material& m, const Matrix83& x_n,
                             const Matrix83& x_1, Vector24& f, Matrix24* K);

/// Cauchy stress σ = J⁻¹ F S Fᵀ (S from the material, (1.4) for St. Venant–Kirchhoff) at the Gauss points,
/// averaged over the element's current volume, weights wJ·J (docs/results.md "/frames", cauchy_stress).
Eigen::Matrix3d average_cauchy_stress(const ElementGeometry& e, const Material& m, const Matrix83& x);

/// von Mises stress √(3/2 s:s), s = σ − tr(σ)/3 · 1 (docs/results.md "/frames", von_mises).
double von_mises(const Eigen::Matrix3d& sigma);

/// Consistent mass M_IJ = Σ_g wJ ρ N_I N_J (1.9), scalar 8×8.
Matrix8 consistent_mass(const ElementGeometry& e, double density);

}  // namespace stoss::fem
