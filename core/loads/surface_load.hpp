#pragma once
/// @file What the surface loads share (docs/theory.md §5b): the step's evaluation under the scheme's force
/// rule, the load's own clock, and the work and impulse it accumulates step by step.

#include <Eigen/Core>
#include <vector>

#include "core/loads/amplitude.hpp"
#include "core/mesh/mesh.hpp"
#include "core/time/term.hpp"

namespace stoss::loads {

using FacePositions = Eigen::Matrix<double, 3, 4>;  ///< a face's node positions as columns
using FaceVector = Eigen::Matrix<double, 12, 1>;    ///< 3 per face node, in face order
using FaceMatrix = Eigen::Matrix<double, 12, 12>;

/// An external load on faces: adds −force_factor · f_alg to the position rows (f_alg the load's algorithmic
/// force (5b.4)) and, for a follower load, its tangent. Not conservative: energy() is 0 and the load's
/// work is counted by work() instead, in the step's own discrete form (5b.5).
class SurfaceLoad : public time::Term {
 public:
  void register_blocks(solve::BlockPattern& pattern) override;
  /// Caches a(t_n) f(x_n) when the rule weighs the step's start (HHT-α, generalized-α).
  void begin_step(const time::StepContext& step, Eigen::VectorXd& z) override;
  void add(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
           solve::BlockPattern* K) const override;
  /// Adds the step's work (f_alg·Δx, or the trapezoid rule between two equilibria) and impulse to the
  /// totals and advances the load's clock by h.
  void end_step(const time::StepContext& step, const Eigen::VectorXd& z) override;
  /// "time", "work" and "impulse": the clock and the totals (a checkpoint's record of the load).
  time::TermState save_state() const override;
  void restore_state(const time::TermState& state, const Eigen::VectorXd& x,
                     const Eigen::VectorXd& v) override;

  /// Σ over the converged steps of f_alg·Δx (5b.5), in static steps of the trapezoid rule (5b.7b): what
  /// the load adds to series/external_work.
  double work() const { return work_; }
  /// Σ over the converged steps of force_factor · Σ_I f_alg,I: the load's impulse on the bodies.
  const Eigen::Vector3d& impulse() const { return impulse_; }
  /// t_n of the next step: the start time plus every converged step's h.
  double time() const { return t_; }
  /// Sets t_n (the run may keep the load's clock on its own, e.g. after a step reduction's substeps).
  void set_time(double t) { t_ = t; }
  /// f_alg of the step at x_1, stacked like the positions (3 per node, 0 off the surface).
  Eigen::VectorXd step_force(const time::StepContext& step, const Eigen::VectorXd& x_1) const;
  const std::vector<mesh::Quad>& faces() const { return faces_; }
  const Amplitude& amplitude() const { return amplitude_; }

 protected:
  SurfaceLoad(std::vector<mesh::Quad> faces, Amplitude amplitude, double start_time);
  /// The force of face k at positions x for a unit amplitude (12 entries), and ∂f/∂x if K is given.
  virtual void face_force(size_t k, const FacePositions& x, FaceVector& f, FaceMatrix* K) const = 0;
  /// Whether the force depends on the positions (a follower load): only then it has a tangent.
  virtual bool follows_deformation() const = 0;

 private:
  /// Where, when and with which weights the step evaluates the load (5b.4).
  struct Evaluation {
    double theta, weight, previous_weight, factor;
  };
  Evaluation evaluation(const time::StepContext& step) const;
  /// f_alg of face k at x_1 and, if K is given, ∂f_alg/∂x_1.
  void face_step(const time::StepContext& step, const Evaluation& e, size_t k, const Eigen::VectorXd& x_1,
                 FaceVector& f, FaceMatrix* K) const;

  std::vector<mesh::Quad> faces_;
  Amplitude amplitude_;
  double t_ = 0;
  double work_ = 0;
  Eigen::Vector3d impulse_ = Eigen::Vector3d::Zero();
  std::vector<int> block_;
  std::vector<FaceVector> force_n_;  ///< a(t_n) f(x_n) per face, for the rules that weigh it and static steps
};

}  // namespace stoss::loads
