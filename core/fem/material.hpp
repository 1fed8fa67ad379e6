#pragma once
/// @file Hyperelastic materials behind one interface: the energy density W, the second Piola–Kirchhoff
/// stress S = ∂W/∂E and its tangent ∂S/∂E as functions of the Green–Lagrange strain E = ½(C − 1)
/// (equivalently of C), and the discrete stress the energy–momentum scheme needs (docs/theory.md §1.2,
/// §2.3, §2.6). A material is one file; make_material (material.cpp) is the registry.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/model/model.hpp"

namespace stoss::fem {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

/// Voigt order [11, 22, 33, 23, 13, 12]; stresses by their components.
Vector6d to_voigt_stress(const Eigen::Matrix3d& S);

/// The Voigt matrix D of a linear map δE ↦ δS (both symmetric): δS_voigt = D δE_voigt with engineering
/// shear strains (2 δE_23, 2 δE_13, 2 δE_12), the convention of the element's B matrix.
template <class LinearMap>
Matrix6d voigt_matrix(const LinearMap& map) {
  static constexpr int row[6] = {0, 1, 2, 1, 0, 0}, col[6] = {0, 1, 2, 2, 2, 1};
  Matrix6d D;
  for (int k = 0; k < 6; ++k) {
    Eigen::Matrix3d dE = Eigen::Matrix3d::Zero();
    const double value = k < 3 ? 1.0 : 0.5;  // an engineering shear of 1 is δE_ij = δE_ji = ½
    dE(row[k], col[k]) = value;
    dE(col[k], row[k]) = value;
    D.col(k) = to_voigt_stress(map(dE));
  }
  return D;
}

class Material {
 public:
  virtual ~Material() = default;
  virtual std::string name() const = 0;
  /// W(E), per unit reference volume.
  virtual double energy_density(const Eigen::Matrix3d& E) const = 0;
  /// S = ∂W/∂E, and ∂S/∂E in Voigt form (voigt_matrix) into *tangent when it is not null: one
  /// evaluation for both, as the element needs them together at every Gauss point.
  virtual Eigen::Matrix3d evaluate_stress(const Eigen::Matrix3d& E, Matrix6d* tangent) const = 0;
  /// A symmetric stress S_alg with W(E_b) − W(E_a) = S_alg : (E_b − E_a) to round-off (2.6), which
  /// tends to S(E) as E_a, E_b → E: the energy–momentum scheme's stress; ∂S_alg/∂E_b in Voigt form into
  /// *tangent when it is not null.
  virtual Eigen::Matrix3d evaluate_discrete_stress(const Eigen::Matrix3d& E_a, const Eigen::Matrix3d& E_b,
                                                   Matrix6d* tangent) const = 0;

  /// The parts of the two evaluations alone.
  Eigen::Matrix3d stress(const Eigen::Matrix3d& E) const { return evaluate_stress(E, nullptr); }
  Matrix6d tangent(const Eigen::Matrix3d& E) const {
    Matrix6d D;
    evaluate_stress(E, &D);
    return D;
  }
  Eigen::Matrix3d discrete_stress(const Eigen::Matrix3d& E_a, const Eigen::Matrix3d& E_b) const {
    return evaluate_discrete_stress(E_a, E_b, nullptr);
  }
  Matrix6d discrete_stress_tangent(const Eigen::Matrix3d& E_a, const Eigen::Matrix3d& E_b) const {
    Matrix6d D;
    evaluate_discrete_stress(E_a, E_b, &D);
    return D;
  }
};

/// The names make_material knows, for validation and the schema.
const std::vector<std::string_view>& material_models();

/// The material a body asks for (model::Material::model: "saint_venant_kirchhoff", "neo_hookean").
/// @throws std::invalid_argument naming an unknown model.
std::shared_ptr<const Material> make_material(const model::Material& spec);

/// Lamé parameters (1.5) from Young's modulus and Poisson's ratio.
struct Lame {
  double lambda, mu;
  static Lame from(double youngs_modulus, double poisson_ratio);
};

}  // namespace stoss::fem
