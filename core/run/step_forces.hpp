#pragma once
/// @file The per-item forces a step reports (series reaction_force and contact_force, docs/results.md)
/// from those of its converged substeps.

#include <Eigen/Core>
#include <vector>

namespace stoss::run {

/// Σ h_k f_k / Σ h_k over a step's substeps, so that the step's force times h is the substeps' impulse;
/// exactly the substep's force when there is one (docs/theory.md §5b.9).
class StepForces {
 public:
  void clear() { *this = StepForces(); }
  void add(double h, const std::vector<Eigen::Vector3d>& forces);
  std::vector<Eigen::Vector3d> step_forces() const;
  /// The last substep's forces: what a static step reports, the equilibrium at its load level, however many
  /// substeps reached it (docs/theory.md §5b.9).
  const std::vector<Eigen::Vector3d>& end_forces() const { return last_; }

 private:
  std::vector<Eigen::Vector3d> impulse_, last_;
  double h_ = 0;
  int substeps_ = 0;
};

}  // namespace stoss::run
