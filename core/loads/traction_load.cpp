#include "core/loads/traction_load.hpp"

#include <stdexcept>

#include "core/loads/face_quadrature.hpp"

namespace stoss::loads {

TractionLoad::TractionLoad(std::vector<mesh::Quad> faces, const Eigen::VectorXd& X,
                           const Eigen::Vector3d& traction, Amplitude amplitude, double start_time)
    : SurfaceLoad(std::move(faces), std::move(amplitude), start_time), traction_(traction) {
  if (!traction.allFinite()) throw std::invalid_argument("traction: a load must be finite");
  weights_.reserve(this->faces().size());
  for (const mesh::Quad& face : this->faces()) {
    const FacePositions X_face = face_positions(face, X);
    Eigen::Vector4d w = Eigen::Vector4d::Zero();
    for (const FacePoint& g : face_gauss_points())
      w += area_normal(g, X_face).norm() * Eigen::Vector4d(g.N.data());
    weights_.push_back(w);
  }
}

void TractionLoad::face_force(size_t k, const FacePositions&, FaceVector& f, FaceMatrix* K) const {
  for (int I = 0; I < 4; ++I) f.segment<3>(3 * I) = weights_[k][I] * traction_;  // (5b.2)
  if (K) K->setZero();
}

}  // namespace stoss::loads
