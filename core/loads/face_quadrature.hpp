#pragma once
/// @file The bilinear quad of a boundary face and its 2×2 Gauss rule (docs/theory.md §5b.2).

#include <Eigen/Core>
#include <array>

#include "core/mesh/mesh.hpp"

namespace stoss::loads {

/// Shape functions of the face (a, b, c, d) at one Gauss point, nodes at (ξ, η) = (−,−), (+,−), (+,+), (−,+),
/// so that x_ξ × x_η points out of the body for a face in outward order (docs/theory.md §1.1).
struct FacePoint {
  std::array<double, 4> N, dN_dxi, dN_deta;
};

/// The 2×2 Gauss points, all weights 1: exact for every integrand of §5b (biquadratic at most).
const std::array<FacePoint, 4>& face_gauss_points();

/// The face's four node positions as columns, from stacked positions x.
Eigen::Matrix<double, 3, 4> face_positions(const mesh::Quad& face, const Eigen::VectorXd& x);

/// x_ξ × x_η at a Gauss point: the outward normal times the area per unit parent area (5b.2).
Eigen::Vector3d area_normal(const FacePoint& g, const Eigen::Matrix<double, 3, 4>& x);

}  // namespace stoss::loads
