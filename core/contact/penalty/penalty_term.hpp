#pragma once
/// @file Frictional penalty contact of one pair as a time::Term (docs/theory.md §5): no auxiliary
/// unknowns; per step every near slave node gets one master face, fixed for the step (§3.4), and
/// the element of §5.2 adds h·(5.2) and its non-symmetric tangent: penalty_element() on a faceted
/// master, patch_penalty_element() on the face's patch of a smooth one
/// (docs/smooth_master_surface.md §3.8). The friction history is
/// committed in end_step only (§5.2 item 7).

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "core/contact/contact_term.hpp"
#include "core/contact/geometry/broad_phase.hpp"
#include "core/contact/geometry/surface.hpp"
#include "core/contact/penalty/penalty_element.hpp"
#include "core/model/model.hpp"

namespace stoss::contact {

/// One slave node tied to one master face for a step.
struct PenaltyContact {
  int slave = -1;                                  ///< index into PairSurfaces::slave_nodes
  int face = -1;                                   ///< index into PairSurfaces::faces
  Eigen::Vector2d xi_n = Eigen::Vector2d::Zero();  ///< CPP start: ξ of the last step, else of x_n
  FrictionHistory history;                         ///< t_{T,n} (§5.2 item 3)
  double gap_offset = 0;                           ///< kept gap of a switch_gap "keep" pair (§3.4)
  std::vector<int> dofs;                           ///< the element's global dofs (slave first)
  int block = -1;                                  ///< Jacobian block id
};

/// Per slave node, what a converged step leaves for the next (§5.2 item 7).
struct PenaltyNodeState {
  int face = -1;                                 ///< face of the last step; −1: not near the master
  Eigen::Vector2d xi = Eigen::Vector2d::Zero();  ///< ξ_{n+1} on that face
  FrictionHistory history;                       ///< t_{T,n+1}; zero once the contact opened
  double gap_offset = 0;                         ///< kept gap; cleared once the node is clear of both faces
};

/// Penalty contact (5.1)–(5.3) of one pair.
/// @note Face per step: a node near the master keeps last step's face until |ξ_n|_∞ > 1 + ε_sw, then
///       moves to the best face at x_n (§3.4); a node new to the master gets its best face at x_n.
///       The history (a spatial vector) carries across a switch (§5.2 item 3). The report's
///       energy_jump is the change of Σ W_N(x_n) a switch causes; switches counts them. switch_gap
///       "clamp": the penetration is measured against the new face from then on (W_N may jump);
///       "keep": W_N continues from the old face's value through a constant gap offset (no jump), which
///       is cleared once the node is clear of the new face with and without the offset.
/// @note Friction μ = 0 passes ε_T = 0 to the element: no tangential traction and no return mapping
///       (return_map_evaluations() stays 0).
/// @note energy(x) = Σ W_N(g_N(x)) + Σ |t_{T}|²/(2ε_T) (5.1), with the committed history: the penalty
///       energy inside the total H of (5.4) when x is the last converged state.
class PenaltyContactTerm : public ContactTerm {
 public:
  /// `master_youngs_modulus` sets the default stiffnesses 10 E ℓ (§5.1) of the unset ones; `static_steps`
  /// evaluates the elements at x_{n+1} (PenaltyParameters::at_end, docs/theory.md §5b.6).
  PenaltyContactTerm(const mesh::Mesh& mesh, const model::ContactPair& pair, double master_youngs_modulus,
                     bool static_steps = false);
  double energy(const Eigen::VectorXd& x) const override;
  void prepare_step(const time::StepContext& step) override;
  int structure_generation() const override { return generation_; }
  void end_step(const time::StepContext& step, const Eigen::VectorXd& z) override;
  /// Per slave node: face, ξ, friction history, gap offset; the Coulomb work so far (penalty_state.cpp).
  time::TermState save_state() const override;
  void restore_state(const time::TermState& state, const Eigen::VectorXd& x,
                     const Eigen::VectorXd& v) override;

  double dissipated_energy() const override { return dissipated_; }

  const PenaltyParameters& parameters() const { return params_; }
  const std::vector<PenaltyContact>& contacts() const { return contacts_; }
  const std::vector<PenaltyNodeState>& node_states() const { return committed_; }
  /// Closed elements that went through the Coulomb return mapping (5.3), over all evaluations (on several
  /// ranks, the evaluations of this rank's add and of the steps' ends, which every rank makes).
  long return_map_evaluations() const { return return_maps_; }
  /// Slip work t_{n+1}·Δξ_p of the last converged step (0 when every contact stuck).
  double last_slip_work() const { return last_slip_work_; }

 private:
  void register_pair_blocks(solve::BlockPattern& pattern) override;
  void add_pair(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                solve::BlockPattern* K) const override;
  /// Evaluates the element of contact c over the step on the pair's surface and hands its result
  /// (PenaltyResult or PatchPenaltyResult) to use(result).
  template <class Use>
  void evaluate(const PenaltyContact& c, const Eigen::VectorXd& x_n, const Eigen::VectorXd& x_1,
                Use&& use) const;
  int face_for(int slave, const time::StepContext& step, Eigen::Vector2d& xi) const;
  /// Counts a switch of `slave` to `face` at x_n, adds its W_N jump, returns the new gap offset.
  double switch_face(int slave, int face, const Eigen::VectorXd& x_n);

  PenaltyParameters params_;
  std::vector<TensorPatch> local_patches_;  ///< per master face of a smooth surface, renumbered (local_patch)
  std::vector<PenaltyContact> contacts_;    ///< elements of the current step
  std::vector<PenaltyNodeState> committed_;  ///< per slave node, after the last converged step
  int generation_ = 0;
  int switches_ = 0;        ///< face switches at the start of the current step
  double switch_jump_ = 0;  ///< Σ W_N(new face) − W_N(old face) at x_n over them
  bool announced_ = false;
  double dissipated_ = 0, last_slip_work_ = 0;
  mutable long return_maps_ = 0;
};

}  // namespace stoss::contact
