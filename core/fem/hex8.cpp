#include "core/fem/hex8.hpp"

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>
#include <string>

namespace stoss::fem {
namespace {
constexpr double corner[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                 {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
}

ShapeValues hex8_shape(const Eigen::Vector3d& xi) {
  ShapeValues s;
  for (int I = 0; I < 8; ++I) {
    const double a = 1 + xi[0] * corner[I][0], b = 1 + xi[1] * corner[I][1], c = 1 + xi[2] * corner[I][2];
    s.N[I] = 0.125 * a * b * c;  // (1.1)
    s.dN_dxi(I, 0) = 0.125 * corner[I][0] * b * c;
    s.dN_dxi(I, 1) = 0.125 * a * corner[I][1] * c;
    s.dN_dxi(I, 2) = 0.125 * a * b * corner[I][2];
  }
  return s;
}

const std::array<Eigen::Vector3d, 8>& gauss_points() {
  static const std::array<Eigen::Vector3d, 8> points = [] {
    const double g = 1.0 / std::sqrt(3.0);
    std::array<Eigen::Vector3d, 8> p;
    int k = 0;
    for (double c : {-g, g})
      for (double b : {-g, g})
        for (double a : {-g, g}) p[k++] = Eigen::Vector3d(a, b, c);
    return p;
  }();
  return points;
}

std::array<double, 8> jacobian_determinants(const Matrix83& X) {
  std::array<double, 8> det{};
  for (int g = 0; g < 8; ++g) {
    const Eigen::Matrix3d J0 = X.transpose() * hex8_shape(gauss_points()[g]).dN_dxi;  // (1.2)
    det[g] = J0.determinant();
  }
  return det;
}

ElementGeometry precompute_geometry(const Matrix83& X) {
  ElementGeometry e;
  for (int g = 0; g < 8; ++g) {
    const ShapeValues s = hex8_shape(gauss_points()[g]);
    const Eigen::Matrix3d J0 = X.transpose() * s.dN_dxi;  // (1.2)
    const double det = J0.determinant();
    if (!(det > 0))
      throw std::invalid_argument("element is inverted or degenerate: det J0 = " + std::to_string(det) +
                                  " at Gauss point " + std::to_string(g));
    e.gp[g].wJ = det;
    e.gp[g].N = s.N;
    e.gp[g].dN_dX = s.dN_dxi * J0.inverse();
  }
  return e;
}

}  // namespace stoss::fem
