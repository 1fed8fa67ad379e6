#pragma once
/// @file Element stresses for the result frames: Cauchy stress and von Mises per element of a
/// St. Venant–Kirchhoff body, from the nodal positions of a frame.

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "core/fem/material.hpp"
#include "core/model/model.hpp"

namespace stoss::output {

/// Cauchy stress σ = J⁻¹ F S Fᵀ with S = λ tr(E) I + 2μ E, E = ½(FᵀF − I), at the 2×2×2 Gauss points of each
/// hexahedron, averaged over the element's current volume (weights J det J0).
class ElementStress {
 public:
  /// Precomputes ∇_X N at the Gauss points and λ, μ of each element's body. Not available() when the
  /// model lacks a material for some body (then frames carry no stress).
  explicit ElementStress(const model::Model& model);
  bool available() const { return available_; }

  /// σ of every element as 6 values in XDMF Tensor6 order (xx, xy, xz, yy, yz, zz), E × 6 row-major, and
  /// von Mises √(3/2 s:s), s = σ − tr(σ)/3 I, one per element. `positions`: 3 per node.
  void compute(const Eigen::VectorXd& positions, std::vector<double>& cauchy, std::vector<double>& von_mises) const;

 private:
  using Gradients = Eigen::Matrix<double, 8, 3>;  ///< rows ∇_X N_I
  struct GaussPoint {
    Gradients dN_dX;
    double wJ0 = 0;
  };
  bool available_ = false;
  std::vector<mesh::Hex> hex8_;
  std::vector<std::array<GaussPoint, 8>> gauss_;
  std::vector<std::shared_ptr<const fem::Material>> material_;  ///< per element
};

}  // namespace stoss::output
