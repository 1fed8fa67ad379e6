#pragma once
/// @file What every contact term of a pair reports to the run (docs/results.md): the per-step contact
/// row, the nodal contact pressure and the Coulomb work. Lagrange (lagrange_term.hpp) and penalty
/// (penalty_term.hpp) terms implement it.

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "core/contact/geometry/broad_phase.hpp"
#include "core/contact/geometry/surface.hpp"
#include "core/mesh/mesh.hpp"
#include "core/model/model.hpp"
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
  int outside_footprint =
      0;  ///< those of `unassigned` beyond the master's boundary: no blind spot, not logged
  double max_faceted_penetration = 0;  ///< smooth master: near slave nodes against the mesh's own faces
  int slipping = 0;  ///< closed penalty contacts on the Coulomb cone (5.3) in the step; 0 if frictionless
  double max_new_gap_target =
      0;  ///< largest gap target f_3 of the elements activated or switched in the step
  double contact_area =
      0;  ///< Σ of the tributary areas A_I of the slave nodes in contact with a force (series/contact_area)
};

/// A contact pair as a time::Term, with what the run reports of it: the pair, its surfaces and broad
/// phase, the last converged step's report and nodal pressures (what every enforcement shares).
/// @note On several MPI ranks (core/parallel/element_share.hpp) each rank computes the contact rows of the
///       slave nodes it owns (computes()); add() then sums the pair's rows of R and its entries of K over the
///       ranks, so that every rank holds all of them (docs/many_machines.md, "One run on several MPI ranks").
///       The search, the active set and the report stay one computation on every rank, from the same bits.
class ContactTerm : public time::Term {
 public:
  /// Collects the pair's surfaces (surface.hpp: throws naming a missing or empty surface).
  ContactTerm(const mesh::Mesh& mesh, const model::ContactPair& pair);
  std::string name() const override { return "contact " + pair_.slave + " on " + pair_.master; }
  /// Registers the pair's blocks (register_pair_blocks) and remembers which they are.
  void register_blocks(solve::BlockPattern& pattern) final;
  /// One process: add_pair. Several ranks: add_pair for this rank's slave nodes, then the sum over the ranks.
  void add(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
           solve::BlockPattern* K) const final;
  void set_auxiliary_offset(int offset) final { offset_ = offset; }
  /// The last converged step's report.
  const ContactReport& report() const { return report_; }
  /// The frozen gap of the step's new contacts (ContactReport::max_new_gap_target; Term::event_offset).
  double event_offset() const override { return report_.max_new_gap_target; }
  /// Sets p_I (force per area: the node's normal contact force over its tributary area A_I,
  /// surface.hpp) at the slave nodes in contact in the last converged step; other entries untouched.
  void contact_pressure(Eigen::VectorXd& p) const;
  /// Coulomb work D = Σ t_{n+1}·Δξ_p accumulated over the converged steps (§5.2 item 7, ≥ 0); 0 for
  /// frictionless pairs.
  virtual double dissipated_energy() const { return 0; }
  const PairSurfaces& surfaces() const { return surfaces_; }

 protected:
  /// Registers the Jacobian blocks the pair's add_pair writes (Term::register_blocks).
  virtual void register_pair_blocks(solve::BlockPattern& pattern) = 0;
  /// Adds the rows of the slave nodes this rank computes (computes(); all of them on one process) to R, and
  /// their derivatives to K if given (Term::add): into the pair's rows and blocks only.
  virtual void add_pair(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                        solve::BlockPattern* K) const = 0;
  /// Whether this rank computes the rows of slave `slave` (index into surfaces_.slave_nodes): the rank that
  /// owns the node; every slave on a process of its own.
  bool computes(int slave) const;
  /// Sends "<name>: <line>" to the run's solver log, if any.
  void log(const time::StepContext& step, const std::string& line) const;
  /// Records the normal contact force (≥ 0) of slave `slave` (index into surfaces_.slave_nodes) as a
  /// pressure for contact_pressure(); its area counts in contact_area when it carries a force (an active
  /// node with a tensile multiplier, kept by §3.5's anti-cycling, reports pressure 0 and no area).
  void add_pressure(int slave, double force) {
    pressure_.emplace_back(surfaces_.slave_nodes[slave], force / surfaces_.tributary_area[slave]);
    if (force > 0) report_.contact_area += surfaces_.tributary_area[slave];
  }
  /// Forgets the last step's pressures and contact area (before add_pressure of the next).
  void clear_pressure() {
    pressure_.clear();
    report_.contact_area = 0;
  }
  /// Sets the report's max_penetration and unassigned at x (§3.4): every near slave node (broad_)
  /// against the closest master face that accepts it, whichever it is; a node level with the surface
  /// that no face accepts counts as unassigned (the NTS blind spot) and is logged.
  void measure_closest_penetration(const time::StepContext& step, const Eigen::VectorXd& x);
  /// Sets the report's max_faceted_penetration: near slave nodes against the closest bilinear face of
  /// the mesh that accepts them (ε_ext), for a pair whose contact uses the smooth surface.
  void measure_faceted_penetration(const Eigen::VectorXd& x);
  /// v in the log's "%.3e" format.
  static std::string scientific(double v);

  model::ContactPair pair_;
  PairSurfaces surfaces_;
  BroadPhase broad_;
  ContactReport report_;
  std::vector<std::pair<int, double>> pressure_;  ///< (node, pressure) of the last converged step
  int offset_ = 0;                                ///< where the pair's auxiliary unknowns start in z

 private:
  /// Several ranks: add_pair for this rank's slave nodes, then the pair's rows of R and entries of K summed
  /// over the ranks, each added to what the other terms put there.
  void add_on_ranks(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                    solve::BlockPattern* K) const;

  std::vector<int> surface_rows_;        ///< the position rows of the slave and master nodes, ascending
  int first_block_ = 0, end_block_ = 0;  ///< the pair's blocks in the pattern (register_blocks)
  mutable int slots_generation_ = -1;    ///< the pattern generation slots_ belong to
  mutable std::vector<int> slots_;       ///< K's values of the pair's blocks (BlockPattern::slots_of)
};

}  // namespace stoss::contact
