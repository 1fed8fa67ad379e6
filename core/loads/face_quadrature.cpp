#include "core/loads/face_quadrature.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace stoss::loads {
namespace {

std::array<FacePoint, 4> make_points() {
  constexpr std::array<double, 4> xi_I{-1, 1, 1, -1}, eta_I{-1, -1, 1, 1};
  const double g = 1 / std::sqrt(3.0);
  const std::array<std::array<double, 2>, 4> at{{{-g, -g}, {g, -g}, {g, g}, {-g, g}}};
  std::array<FacePoint, 4> out{};
  for (int p = 0; p < 4; ++p)
    for (int I = 0; I < 4; ++I) {
      const double xi = at[p][0], eta = at[p][1];
      out[p].N[I] = 0.25 * (1 + xi * xi_I[I]) * (1 + eta * eta_I[I]);
      out[p].dN_dxi[I] = 0.25 * xi_I[I] * (1 + eta * eta_I[I]);
      out[p].dN_deta[I] = 0.25 * eta_I[I] * (1 + xi * xi_I[I]);
    }
  return out;
}

}  // namespace

const std::array<FacePoint, 4>& face_gauss_points() {
  static const std::array<FacePoint, 4> points = make_points();
  return points;
}

Eigen::Matrix<double, 3, 4> face_positions(const mesh::Quad& face, const Eigen::VectorXd& x) {
  Eigen::Matrix<double, 3, 4> out;
  for (int I = 0; I < 4; ++I) out.col(I) = x.segment<3>(3 * face[I]);
  return out;
}

Eigen::Vector3d area_normal(const FacePoint& g, const Eigen::Matrix<double, 3, 4>& x) {
  const Eigen::Vector3d x_xi = x * Eigen::Vector4d(g.dN_dxi.data());
  const Eigen::Vector3d x_eta = x * Eigen::Vector4d(g.dN_deta.data());
  return x_xi.cross(x_eta);  // (5b.2)
}

}  // namespace stoss::loads
