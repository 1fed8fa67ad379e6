#pragma once
/// @file A follower pressure on faces (scene `loads[i].pressure`; docs/theory.md §5b.2).

#include "core/loads/surface_load.hpp"

namespace stoss::loads {

/// f_I = −a(t) p Σ_g N_I (x_ξ × x_η): normal to the deformed face, positive pushing into the body (5b.2),
/// with the consistent tangent (5b.3). Faces in outward order (docs/theory.md §1.1).
class PressureLoad : public SurfaceLoad {
 public:
  /// `faces` hold global node indices; the load's clock starts at `start_time`.
  /// @throws std::invalid_argument unless the pressure is finite.
  PressureLoad(std::vector<mesh::Quad> faces, double pressure, Amplitude amplitude = {},
               double start_time = 0);
  std::string name() const override { return "pressure"; }
  double pressure() const { return pressure_; }

 protected:
  void face_force(size_t k, const FacePositions& x, FaceVector& f, FaceMatrix* K) const override;
  bool follows_deformation() const override { return true; }

 private:
  double pressure_;
};

}  // namespace stoss::loads
