#pragma once
/// @file Frictionless Lagrange contact in the mixed energy–momentum form (docs/theory.md §4.3): per
/// active element 11 auxiliary unknowns w = (d, ξ, λ) after x_{n+1} in z.

#include "core/contact/lagrange/elements/patch_mixed_element.hpp"
#include "core/contact/lagrange/lagrange_term.hpp"

namespace stoss::contact {

/// The contact term of the energy_momentum scheme: (4.9)–(4.10) per element, energy identity (4.11).
/// @note Auxiliary layout of element k at offset o_k = offset + 11 k: d at o_k, ξ at o_k + 3, λ at o_k + 5.
/// @note Measures: the R_d, R_ξ rows (momentum × length) are divided by (momentum scale × face size
///       ℓ); the constraint rows g_1, g_2, g_3 by ℓ, g_4 as is, g_5, g_6 by ℓ². Increments: |Δd|, |Δξ|
///       (dimensionless); λ is not measured (the rows it enters are).
class MixedContactTerm final : public LagrangeContactTerm {
 public:
  using LagrangeContactTerm::LagrangeContactTerm;
  double auxiliary_residual_measure(const Eigen::VectorXd& R, const time::MeasureScales& s) const override;
  double auxiliary_increment_measure(const Eigen::VectorXd& dz, const time::MeasureScales& s) const override;
  /// velocity_correction pairs: b += h λ_1 ∂g_1/∂x (q_{n+1}) over the elements with a jump, and ΔH of (4.11)
  /// (4.12).
  void add_impact_impulse(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& b,
                          double& energy_jump) const override;

 protected:
  void add_pair(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                solve::BlockPattern* K) const override;
  int unknowns_per_element() const override { return 11; }
  void write_auxiliaries(const ContactElement& e, const Eigen::VectorXd& z_x, int offset,
                         Eigen::VectorXd& z) const override;
  void read_auxiliaries(ContactElement& e, const Eigen::VectorXd& z, int offset) const override;
  Vector6 start_residual(const ContactElement& e, const Eigen::VectorXd& x_n) const override;

 private:
  /// The smooth-surface path: patch_mixed_element per element (docs/smooth_master_surface.md §3).
  void add_smooth(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                  solve::BlockPattern* K) const;
  PatchMixedState patch_state(const ContactElement& e, const Eigen::VectorXd& x, const Eigen::Vector3d& d,
                              const Eigen::Vector2d& xi) const;
  Vector20 coordinates(const ContactElement& e, const Eigen::VectorXd& x, const Eigen::Vector3d& d,
                       const Eigen::Vector2d& xi) const;
};

}  // namespace stoss::contact
