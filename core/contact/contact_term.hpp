#pragma once
/// @file What every contact term of a pair reports to the run (service.md §3): the per-step contact
/// row, the nodal contact pressure and the Coulomb work. Lagrange (lagrange_term.hpp) and penalty
/// (penalty_term.hpp) terms implement it.

#include <Eigen/Core>

#include "core/time/term.hpp"

namespace stoss::contact {

/// What a pair reports after each converged step.
/// @note max_penetration is measured against the closest master face that accepts the node (§3.4,
///       whichever face it is, active or not); max_own_face_penetration only for active nodes, against
///       the face they are assigned to (it stays at the Newton tolerance, §3.4).
/// @note energy_jump = Σ_s λ_s·g_s(π_n) over the elements activated or moved to another face in the
///       step: the energy change of the step by (4.11) with the mixed form (the other elements satisfy
///       g(π_n) = 0 to the Newton tolerance), exactly 0 in steps without either; with the midpoint
///       form Σ λ_1 (g_N(x_n) − f_3), an analogue without that identity. Penalty pairs: the change of
///       W_N at x_n when a node moves to another face (the penalty analogue of the switch jump, §3.4).
struct ContactReport {
  int active = 0;
  double max_penetration = 0;
  double max_own_face_penetration = 0;
  double energy_jump = 0;
  int activations = 0, releases = 0, switches = 0;
  int unassigned = 0;  ///< near slave nodes level with the surface that no face accepts (NTS blind spot)
  int slipping = 0;    ///< closed penalty contacts on the Coulomb cone (5.3) in the step; 0 if frictionless
};

/// A contact pair as a time::Term, with what the run reports of it.
class ContactTerm : public time::Term {
 public:
  /// The last converged step's report.
  virtual const ContactReport& report() const = 0;
  /// Sets p_I (force per area) at the slave nodes in contact in the last converged step; other
  /// entries untouched.
  virtual void contact_pressure(Eigen::VectorXd& p) const = 0;
  /// Coulomb work D = Σ t_{n+1}·Δξ_p accumulated over the converged steps (§5.2 item 7, ≥ 0); 0 for
  /// frictionless pairs.
  virtual double dissipated_energy() const { return 0; }
};

}  // namespace stoss::contact
