#pragma once
/// @file Trilinear hexahedron: shape functions, 2×2×2 Gauss rule, reference-geometry precomputation.

#include <Eigen/Core>
#include <array>

namespace stoss::fem {

using Matrix83 = Eigen::Matrix<double, 8, 3>;
using Vector8 = Eigen::Matrix<double, 8, 1>;

/// Shape function values N_I(ξ) and derivatives ∂N_I/∂ξ (docs/theory.md (1.1)).
struct ShapeValues {
  Vector8 N;
  Matrix83 dN_dxi;
};
ShapeValues hex8_shape(const Eigen::Vector3d& xi);

/// The eight Gauss points ±1/√3 (weights 1), ordered ξ fastest.
const std::array<Eigen::Vector3d, 8>& gauss_points();

/// Precomputed reference data of one Gauss point (docs/theory.md (1.2)).
struct GaussPoint {
  double wJ = 0;   ///< weight × det J0
  Vector8 N;       ///< shape values
  Matrix83 dN_dX;  ///< ∇_X N_I as rows
};

/// Reference geometry of one element: its 8 Gauss points.
struct ElementGeometry {
  std::array<GaussPoint, 8> gp;
};

/// det J0 at each Gauss point for the element's reference nodes X (rows).
std::array<double, 8> jacobian_determinants(const Matrix83& X);

/// Precomputes the Gauss data; throws std::invalid_argument if any det J0 ≤ 0.
ElementGeometry precompute_geometry(const Matrix83& X);

}  // namespace stoss::fem
