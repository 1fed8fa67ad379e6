#pragma once
/// @file A dead traction per unit reference area on faces (scene `loads[i].traction`; docs/theory.md §5b.2).

#include "core/loads/surface_load.hpp"

namespace stoss::loads {

/// f_I = a(t) t Σ_g N_I |X_ξ × X_η| (5b.2): the same nodal forces whatever the body does.
class TractionLoad : public SurfaceLoad {
 public:
  /// `faces` hold global node indices into the stacked reference positions X.
  /// @throws std::invalid_argument unless every traction component is finite.
  TractionLoad(std::vector<mesh::Quad> faces, const Eigen::VectorXd& X, const Eigen::Vector3d& traction,
               Amplitude amplitude = {}, double start_time = 0);
  std::string name() const override { return "traction"; }
  const Eigen::Vector3d& traction() const { return traction_; }

 protected:
  void face_force(size_t k, const FacePositions& x, FaceVector& f, FaceMatrix* K) const override;
  bool follows_deformation() const override { return false; }

 private:
  Eigen::Vector3d traction_;
  std::vector<Eigen::Vector4d> weights_;  ///< per face: Σ_g N_I |X_ξ × X_η|, the nodes' shares of its area
};

}  // namespace stoss::loads
