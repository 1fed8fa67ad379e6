#pragma once
/// @file Frictionless mortar contact of one pair with dual Lagrange multipliers on the slave nodes
/// (docs/theory.md §4.7, (4.81)–(4.84)), on the faceted master surface, for the configuration force rules
/// (midpoint, HHT-α, generalized-α) and the discrete-gradient rule of energy_momentum (§4.7.2, (4.87)).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "core/contact/contact_term.hpp"
#include "core/contact/mortar/pair_derivatives.hpp"
#include "core/parallel/worker_threads.hpp"

namespace stoss::contact {

/// One multiplier λ_j per slave node, after x_{n+1} in z (all slave nodes: the layout never changes).
/// - momentum rows  h [w Σ_j λ_j ∂g̃_j/∂x (x_θ) + w_n Σ_j λ_j,n ∂g̃_j/∂x (x_n)]   (4.82)
///                  energy_momentum: h Σ_j λ_j G_j, G_j the discrete gradient of g̃_j per face pair (4.87)
/// - active j:      g̃_j(x_{n+1}; ḡ⁰_j) − g̃⁰_j = ∫ Φ_j (g − ḡ⁰_j) ψ − g̃⁰_j = 0;  inactive j:  λ_j = 0  (4.83)
/// - active set on the weighted gaps: j activates when g̃_j / D_jj < −1e-10 ℓ and D_jj covers half of the
///   support its overlapping slave faces give it, releases when λ_j > 0 (once a step, as §3.5; a static step
///   may take back its own activation once)                                                          (4.84)
/// - contact_pressure p_j = −λ_j: λ_j is conjugate to g̃_j, the node's force is λ_j D_jj n, so −λ_j is that
///   force over D_jj (λ ≤ 0 in compression, §0)                                                 (4.84)
/// Why dual: the assembled D is diagonal, so g̃_j and λ_j are nodal quantities: the active set is
/// decided node by node, −λ_j is the nodal pressure, and the multipliers could be condensed node by
/// node (they are kept as unknowns here, like the NTS multipliers).
/// @note ḡ⁰_j: the nodal gap g̃_j(x_n) / ∫Φ_j(x_n) of a node activated in the step with impact persist or
///       located (the frozen gap of §4.5, held while the node stays active), else 0. Taken off g inside the
///       integral, it vanishes where the gap is uniform, so a slave rim edge lying on a master rim edge is no
///       kink in the force (a weighted-gap target, ∫ Φ_j g = g̃⁰_j, made it one: the colliding bars with
///       mortar stalled in Newton). g̃⁰_j: the weighted gap g̃_j(x_n) of such a node the master does not cover
///       at x_n, where it has no nodal gap, else 0. Both are 0 while j is inactive. ψ: the facing fade
///       (4.76). Located events are not cut (the step runs to its end), and velocity_correction restores no
///       energy (no impact impulse yet): both act as their frozen-gap or closed-gap counterparts.
/// @note series: contact_area is Σ D_jj over the active nodes with λ_j < 0 (their mortar weights, the
///       current area the multipliers act on); contact_force is measured from the rows as for every pair
///       (measured_contact.hpp).
class MortarContactTerm final : public ContactTerm {
 public:
  MortarContactTerm(const mesh::Mesh& mesh, const model::ContactPair& pair, const time::ForceRule& rule);
  void prepare_step(const time::StepContext& step) override;
  void begin_step(const time::StepContext& step, Eigen::VectorXd& z) override;
  int auxiliary_count() const override { return static_cast<int>(surfaces_.slave_nodes.size()); }
  int structure_generation() const override { return generation_; }
  void initialize_auxiliaries(const time::StepContext& step, Eigen::VectorXd& z) override;
  bool update_active_set(const time::StepContext& step, const Eigen::VectorXd& z) override;
  void end_step(const time::StepContext& step, const Eigen::VectorXd& z) override;
  double auxiliary_residual_measure(const Eigen::VectorXd& R, const time::MeasureScales& s) const override;
  /// Checkpoint: the committed active set, λ_n and the frozen nodal gaps ḡ⁰_j; the face pairs are found
  /// again.
  time::TermState save_state() const override;
  void restore_state(const time::TermState& state, const Eigen::VectorXd& x,
                     const Eigen::VectorXd& v) override;

  /// Per slave node: active in the current pass.
  const std::vector<char>& active() const { return active_; }
  /// Assembled weighted gaps g̃_j (less the frozen nodal gaps, (4.83)) and mortar weights D_jj at positions
  /// x (the step's face pairs); `support`: Σ ψ_s ∫ N_j (a quarter of the area) over j's slave faces s that
  /// overlap some master face at x, ψ_s the largest fade (4.76) of those overlaps (4.84); `pairs`: each face
  /// pair's values, in the order of the pairs.
  void nodal_gaps(const Eigen::VectorXd& x, Eigen::VectorXd& gap, Eigen::VectorXd& weight,
                  Eigen::VectorXd* support = nullptr, std::vector<mortar::PairGaps>* pairs = nullptr) const;

 private:
  void register_pair_blocks(solve::BlockPattern& pattern) override;
  void add_pair(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                solve::BlockPattern* K) const override;
  /// A slave face against a master face that may overlap in this step.
  struct FacePair {
    int slave_face = -1, master_face = -1;
    std::array<int, 4> slave_index;  ///< into surfaces_.slave_nodes
    std::vector<int> dofs;           ///< 24 position dofs then the 4 multiplier rows
    int block = -1;                  ///< in the pattern while a slave node of the pair is active, else −1
    std::optional<Eigen::Matrix<double, 1, 24>> force_n;  ///< λ_n · ∂g̃/∂x(x_n) if the rule weighs it, λ_n ≠ 0
    Eigen::Vector4d gap_n = Eigen::Vector4d::Zero();  ///< this pair's g̃_j at x_n with no frozen gap (4.87)
    Eigen::Vector4d basis_integral_n = Eigen::Vector4d::Zero();  ///< this pair's ∫ Φ_j at x_n
  };
  /// The pair's slave nodes' frozen nodal gaps ḡ⁰_j (4.83).
  Eigen::Vector4d frozen_gaps(const FacePair& p) const;
  /// The pair's g̃_j(x_n; ḡ⁰_j) (4.83), (4.87).
  Eigen::Vector4d gaps_at_start(const FacePair& p) const;
  /// The gaps and their gradient at x.
  mortar::PairGaps gaps(const FacePair& p, const Eigen::VectorXd& x) const;
  /// The gaps and D_jj at x, values only (no gradient).
  mortar::PairGaps gap_values(const FacePair& p, const Eigen::VectorXd& x) const;
  /// λ_n · ∂g̃/∂x(x_n) of (4.82), constant through the step: once in prepare_step, not at every Newton
  /// iteration.
  std::optional<Eigen::Matrix<double, 1, 24>> previous_force(const FacePair& p,
                                                             const Eigen::VectorXd& x_n) const;
  void find_face_pairs(const time::StepContext& step);
  /// D_jj covers enough of the node's support for g̃_j / D_jj to be a gap (4.84).
  static bool covered(double weight, double support);
  /// The pair's 24 position dofs and its 4 multiplier rows (at the current offset).
  void set_dofs(FacePair& p) const;
  /// Whether a slave node of the pair is active: only such pairs have rows and a block (register_blocks).
  bool has_active_node(const FacePair& p) const;
  /// A new structure generation when the pairs with an active node are not those with a block.
  void refresh_structure();
  /// Makes slave node j inactive: λ_j = 0 and no frozen gap.
  void release(int j);
  /// Releases the active slave nodes that no master face overlaps at x_n (D_jj = 0): their row (4.83) would
  /// be zero, the Jacobian singular (a body leaving contact; the seed example failed so at t = 0.93).
  void release_uncovered();
  /// Static steps (pair closes_touching): slave nodes whose nodal gap g̃_j / D_jj at x_n is at most 1e-8 ℓ
  /// start the step active, as the NTS term's (a body held by this contact alone has no other support).
  void activate_touching();
  /// One face pair's share of add: its 24 position rows and 4 multiplier rows, and its 28 × 28 block.
  struct PairContribution {
    Eigen::Matrix<double, 28, 1> rows;
    Eigen::Matrix<double, 28, 28> block;
    bool tangent = false;  ///< block is set
    bool failed = false;   ///< the integrals threw: a folded projection
  };
  /// One face pair's rows (and with `tangent` its block) of add (4.81)–(4.83), without λ_n's part. Throws
  /// what the integrals throw on a folded projection. x_1 = z's positions, x_θ the rule's evaluation point:
  /// formed once per add, not per pair. Reads the term only: add runs it on worker threads.
  void pair_contribution(const FacePair& p, const time::StepContext& step, const Eigen::VectorXd& z,
                         const Eigen::VectorXd& x_1, const Eigen::VectorXd& x_theta, bool tangent,
                         PairContribution& out) const;

  time::ForceRule rule_;
  bool exact_energy_ = false;  ///< energy_momentum: the discrete gradient (4.87) instead of ∂g̃/∂x(x_m)
  std::vector<mesh::Quad> slave_faces_;
  std::vector<FacePair> pairs_;
  std::vector<int> diagonal_blocks_;  ///< per slave node: its multiplier row's 1 × 1 block
  int slave_index(int node) const;
  model::ImpactMode impact() const { return pair_.impact; }

  std::vector<char> active_, start_active_, committed_active_;
  std::vector<int> toggles_;
  Eigen::VectorXd lambda_;                        ///< latest multipliers (read back after each solve)
  Eigen::VectorXd lambda_n_;                      ///< λ of the last converged step (t_n)
  Eigen::VectorXd frozen_, committed_frozen_;     ///< ḡ⁰_j (4.83); 0 for an inactive node
  Eigen::VectorXd target_, committed_target_;     ///< g̃⁰_j of a node not covered at x_n (4.83), else 0
  Eigen::VectorXd gap_n_, weight_n_, support_n_;  ///< g̃_j, D_jj and the coverable support at x_n
  Eigen::VectorXd basis_integral_n_;              ///< Σ ∫ Φ_j over j's face pairs at x_n
  double length_ = 1;                             ///< mean master face size ℓ
  mutable std::vector<PairContribution> contributions_;  ///< add's per-pair buffers
  mutable std::unique_ptr<parallel::WorkerThreads> threads_ = std::make_unique<parallel::WorkerThreads>();
  int generation_ = 0;
};

}  // namespace stoss::contact
