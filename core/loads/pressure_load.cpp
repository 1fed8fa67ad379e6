#include "core/loads/pressure_load.hpp"

#include <cmath>
#include <stdexcept>

#include "core/loads/face_quadrature.hpp"

namespace stoss::loads {
namespace {

/// [a]×, the matrix with [a]× b = a × b.
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0, -a[2], a[1], a[2], 0, -a[0], -a[1], a[0], 0;
  return m;
}

}  // namespace

PressureLoad::PressureLoad(std::vector<mesh::Quad> faces, double pressure, Amplitude amplitude,
                           double start_time)
    : SurfaceLoad(std::move(faces), std::move(amplitude), start_time), pressure_(pressure) {
  if (!std::isfinite(pressure)) throw std::invalid_argument("pressure: a load must be finite");
}

void PressureLoad::face_force(size_t, const FacePositions& x, FaceVector& f, FaceMatrix* K) const {
  f.setZero();
  if (K) K->setZero();
  for (const FacePoint& g : face_gauss_points()) {
    const Eigen::Vector3d n = area_normal(g, x);
    for (int I = 0; I < 4; ++I) f.segment<3>(3 * I) -= pressure_ * g.N[I] * n;  // (5b.2)
    if (!K) continue;
    const Eigen::Matrix3d x_xi = cross_matrix(x * Eigen::Vector4d(g.dN_dxi.data()));
    const Eigen::Matrix3d x_eta = cross_matrix(x * Eigen::Vector4d(g.dN_deta.data()));
    for (int J = 0; J < 4; ++J) {
      const Eigen::Matrix3d dn_dxJ = g.dN_deta[J] * x_xi - g.dN_dxi[J] * x_eta;  // (5b.3)
      for (int I = 0; I < 4; ++I) K->block<3, 3>(3 * I, 3 * J) -= pressure_ * g.N[I] * dn_dxJ;
    }
  }
}

}  // namespace stoss::loads
