#pragma once
/// @file Frictionless Lagrange NTS contact for the α-weighted schemes, HHT-α (docs/theory.md §2.4,
/// (2.11)) and generalized-α (§2.5, (2.12)): forces at t_{n+1} and t_n with the weights of the scheme's
/// ForceRule (end point), one multiplier per active element after x_{n+1} in z, like the midpoint form (§4.2).

#include <array>
#include <utility>
#include <vector>

#include "core/contact/lagrange/elements/midpoint_term.hpp"

namespace stoss::contact {

/// The contact term of the end-point force rules, the Gᵀλ part of (2.11) and (2.12) with G = N_sᵀ (3.6):
///   momentum rows   h [w λ_{n+1} N_s(x_{n+1}) + w_n λ_n N_s(x_n)]   (HHT-α: w = 1+α, w_n = −α),
///   constraint row  g_N(x_{n+1}) − f_3 = 0   (enforced at t_{n+1}).
/// @note λ_n N_s(x_n) is the contact force of the last converged step, summed over the elements active
///       at its end (kept from end_step): an element activated in this step has λ_n = 0; an element
///       released in this step keeps its t_n part, as f(x_n) of (2.11) requires.
/// @note Conserves linear momentum (the entries of N_s sum to zero, so both parts are balanced; with
///       the Newmark update (2.10) Σ M a stays 0); neither energy nor angular momentum (§2.4).
///       Multiplier bookkeeping, measures and the impact modes exact / persist are the midpoint form's.
class HhtContactTerm final : public MidpointContactTerm {
 public:
  using MidpointContactTerm::MidpointContactTerm;
  void add(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
           solve::BlockPattern* K) const override;
  /// Commits the step and keeps λ_{n+1} N_s(x_{n+1}) of every active element for the next step.
  void end_step(const time::StepContext& step, const Eigen::VectorXd& z) override;

 private:
  /// (element dofs, λ N_s) of the elements active at the end of the last converged step.
  std::vector<std::pair<std::vector<int>, Eigen::VectorXd>> previous_force_;
};

}  // namespace stoss::contact
