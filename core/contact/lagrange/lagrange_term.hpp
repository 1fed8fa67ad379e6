#pragma once
/// @file Frictionless Lagrange contact of one pair as a time::Term: the active set, the face
/// assignment and the per-step report, shared by the two time discretisations of the constraint
/// (docs/theory.md §3.4, §3.5, §4.2, §4.3, §4.5).

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "core/contact/contact_term.hpp"
#include "core/contact/geometry/assignment.hpp"
#include "core/contact/geometry/broad_phase.hpp"
#include "core/contact/geometry/surface.hpp"
#include "core/contact/types.hpp"
#include "core/model/model.hpp"
#include "core/time/term.hpp"

namespace stoss::contact {

/// One active contact element: a slave node tied to one master face for a whole step (§3.4).
/// @note λ_1 ≤ 0 in compression (docs/theory.md §0); the midpoint form uses lambda[0] only.
struct ContactElement {
  int slave = -1;                    ///< index into PairSurfaces::slave_nodes
  int face = -1;                     ///< index into PairSurfaces::faces
  double f3 = 0;                     ///< gap target π7 (§4.3.1; persist: frozen gap, §4.5)
  Eigen::Vector3d d_n, d;            ///< director at t_n and its latest value (mixed form)
  Eigen::Vector2d xi_n, xi;          ///< convective coordinates at t_n and latest
  Vector6 lambda = Vector6::Zero();  ///< latest multipliers
  Vector6 g_n = Vector6::Zero();     ///< g(π_n) (4.11), fixed within the step
  bool jump = false;                 ///< activated or moved to another face in this step
  int block = -1;                    ///< Jacobian block id
};

/// impact located: an activation or release found inside a step (docs/theory.md §4.6.2).
struct LocatedEvent {
  int slave = -1;   ///< index into PairSurfaces::slave_nodes
  double time = 0;  ///< after t_n, where `value` belongs (the step's end for a gap, λ_1's time for a release)
  double value = 0;     ///< the gap (activation) or λ_1 (release) of this solve
  double fraction = 1;  ///< the step fraction of the zero of `value` (4.14), (4.15)
};

/// The active-set bookkeeping of §3.5 and the search of §3.4 around an element kernel.
/// @note A step that is abandoned (prepare_step again without end_step) is forgotten: the next
///       prepare_step starts from the elements of the last converged step.
/// @note Assignment is frozen within a step; a face switch happens only in prepare_step, with the
///       hysteresis ε_sw of the pair. Activation: a near slave node whose best face at x_{n+1} shows
///       g_N < −1e-10 × face size; release: λ_1 > 0. A node that would toggle a second time in one
///       step stays active (logged), so the loop ends.
class LagrangeContactTerm : public ContactTerm {
 public:
  LagrangeContactTerm(const mesh::Mesh& mesh, const model::ContactPair& pair);
  void prepare_step(const time::StepContext& step) override;
  void begin_step(const time::StepContext& step, Eigen::VectorXd& z) override;
  int auxiliary_count() const override { return static_cast<int>(elements_.size()) * unknowns_per_element(); }
  int structure_generation() const override { return generation_; }
  void initialize_auxiliaries(const time::StepContext& step, Eigen::VectorXd& z) override;
  bool update_active_set(const time::StepContext& step, const Eigen::VectorXd& z) override;
  /// impact located: the step fraction of the earliest activation or release located in the last
  /// update_active_set (§4.6.2), or 1.
  double requested_cut() const override { return cut_; }
  void end_step(const time::StepContext& step, const Eigen::VectorXd& z) override;
  /// The active elements after the last converged step: slave, face, f3, d, ξ, λ (lagrange_state.cpp).
  time::TermState save_state() const override;
  /// Sets the elements and replays end_step at (x, v), so that a subclass rebuilds what it keeps of the
  /// step (HHT: λ_n N_s(x_n)); the elements are then exactly the saved ones (lagrange_state.cpp).
  void restore_state(const time::TermState& state, const Eigen::VectorXd& x,
                     const Eigen::VectorXd& v) override;

  const std::vector<ContactElement>& elements() const { return elements_; }

 protected:
  void register_pair_blocks(solve::BlockPattern& pattern) override;
  /// Auxiliary unknowns of one element (mixed: 11, midpoint: 1).
  virtual int unknowns_per_element() const = 0;
  /// Writes the element's initial auxiliary values at `offset` of z (positions of z: current iterate).
  virtual void write_auxiliaries(const ContactElement& e, const Eigen::VectorXd& z_x, int offset,
                                 Eigen::VectorXd& z) const = 0;
  /// Reads the element's latest values back from a solution z.
  virtual void read_auxiliaries(ContactElement& e, const Eigen::VectorXd& z, int offset) const = 0;
  /// g(π_n) of the element: the constraint residual at the start of the step (4.11).
  virtual Vector6 start_residual(const ContactElement& e, const Eigen::VectorXd& x_n) const = 0;

  int element_offset(int k) const { return offset_ + k * unknowns_per_element(); }
  int slave_node(const ContactElement& e) const { return surfaces_.slave_nodes[e.slave]; }
  const mesh::Quad& face_of(const ContactElement& e) const { return surfaces_.faces[e.face]; }
  double face_size(const ContactElement& e) const { return surfaces_.face_size[e.face]; }
  Eigen::Vector3d position(const ContactElement& e, const Eigen::VectorXd& x) const {
    return x.segment<3>(3 * slave_node(e));
  }
  model::ImpactMode impact() const { return pair_.impact; }

  std::vector<ContactElement> elements_;

 private:
  void switch_face_if_needed(ContactElement& e, const time::StepContext& step);
  ContactElement new_element(int slave, const FaceProjection& at_end, const time::StepContext& step) const;
  bool release_tensile(const time::StepContext& step, const Eigen::VectorXd& z);
  bool activate_penetrating(const time::StepContext& step, const Eigen::VectorXd& z);
  /// Static steps (pair closes_touching): the slave nodes within touching_gap of the master at x_n become
  /// active before the step's first pass.
  void activate_touching(const time::StepContext& step);
  void reindex();
  /// impact located: whether slave i's event must start a step of its own (§4.6.2).
  bool locates(int slave, const time::StepContext& step) const;
  /// The release event of element e with tensile λ_1 (4.15); fraction 0 when it has no compressive past
  /// value.
  LocatedEvent release_event(const ContactElement& e, const time::StepContext& step) const;
  /// The event of `slave` whose value is v1 at t1 and v0 at t0, or at the last cut's solve when that located
  /// the same slave (a secant step, §4.6.2).
  LocatedEvent located(int slave, double t0, double v0, double t1, double v1,
                       const time::StepContext& step) const;
  /// The slave's gap at x_n on `face` (the start of the step).
  double start_gap(int slave, int face, const time::StepContext& step, const Eigen::Vector2d& xi) const;
  /// Turns the earliest of the pass's events into a cut and marks the events it ends at (§4.6.2).
  void request_cut(const time::StepContext& step);

  std::vector<ContactElement> start_;      ///< elements at the start of the step (after switches)
  std::vector<ContactElement> committed_;  ///< elements at the end of the last converged step
  bool in_step_ = false;                   ///< prepare_step called, end_step not yet
  std::vector<int> element_of_;            ///< per slave: index into elements_, or −1
  std::vector<int> start_of_;              ///< per slave: index into start_, or −1
  std::vector<int> toggles_;               ///< per slave: active-set changes in this step
  std::vector<char> released_now_;         ///< per slave: released in the current pass
  int generation_ = 0;

  // impact located (§4.6.2)
  std::vector<LocatedEvent> events_;  ///< located in this pass
  LocatedEvent secant_;               ///< the earliest event of the last cut in this step
  double cut_ = 1;                    ///< the cut asked for by the last update_active_set
  std::vector<char> pending_;         ///< per slave: its event is the one the cut asked for targets
  double pending_time_ = 0;           ///< the cut's time after t_n
  std::vector<char> armed_;           ///< per slave: the last step ended at its event; it toggles now
  double previous_step_ = 0;  ///< h of the last converged step (λ_1 of a midpoint form sits at its middle)
};

}  // namespace stoss::contact
