#pragma once
/// @file Frictionless Lagrange NTS contact for the configuration force rules: the implicit midpoint rule
/// (docs/theory.md §4.2, seed eqs 50–52) and the end-point rules of HHT-α (§2.4, (2.11)) and
/// generalized-α (§2.5, (2.12)); one multiplier per active element after x_{n+1} in z.

#include <array>
#include <utility>
#include <vector>

#include "core/contact/geometry/surface.hpp"
#include "core/contact/lagrange/elements/patch_nts_element.hpp"
#include "core/contact/lagrange/lagrange_term.hpp"

namespace stoss::contact {

/// The NTS contact term of the configuration force rules; the scheme's ForceRule (data, given at
/// construction) picks the element:
/// - midpoint: h λ N_s(x_m) in the momentum rows, g_N(x_{n+1}) − f_3 = 0. Conserves both momenta, not
///   energy (§4.2).
/// - end point, the Gᵀλ part of (2.11) and (2.12) with G = N_sᵀ (3.6):
///     momentum rows   h [w λ_{n+1} N_s(x_{n+1}) + w_n λ_n N_s(x_n)]   (HHT-α: w = 1+α, w_n = −α),
///     constraint row  g_N(x_{n+1}) − f_3 = 0   (enforced at t_{n+1}).
///   λ_n N_s(x_n) is the contact force of the last converged step, summed over the elements active at
///   its end (kept from end_step): an element activated in this step has λ_n = 0; an element released
///   in this step keeps its t_n part, as f(x_n) of (2.11) requires. Conserves linear momentum (the
///   entries of N_s sum to zero, so both parts are balanced; with the Newmark update (2.10) Σ M a stays
///   0); neither energy nor angular momentum (§2.4).
/// @note Measures: the constraint row is divided by the face size; the multiplier increment is not
///       measured (the rows it enters are).
class NtsContactTerm final : public LagrangeContactTerm {
 public:
  /// `rule`: a midpoint or an end-point rule (make_pair_term rejects the others).
  NtsContactTerm(const mesh::Mesh& mesh, const model::ContactPair& pair, const time::ForceRule& rule);
  /// Commits the step; under an end-point rule keeps λ_{n+1} N_s(x_{n+1}) of every active element for
  /// the next step.
  void end_step(const time::StepContext& step, const Eigen::VectorXd& z) override;
  double auxiliary_residual_measure(const Eigen::VectorXd& R, const time::MeasureScales& s) const override;

 private:
  void add_pair(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                solve::BlockPattern* K) const override;
  /// Calls f(element, offset of its auxiliaries) for each active element this rank computes, in order.
  template <class F>
  void for_each_element(F f) const {
    for (size_t k = 0; k < elements_.size(); ++k)
      if (computes(elements_[k].slave)) f(elements_[k], element_offset(static_cast<int>(k)));
  }
  /// The midpoint rows (4.2), and the end-point rows (2.11), (2.12) without the t_n part.
  void add_midpoint(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                    solve::BlockPattern* K) const;
  void add_end_point(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                     solve::BlockPattern* K) const;

  int unknowns_per_element() const override { return 1; }
  void write_auxiliaries(const ContactElement& e, const Eigen::VectorXd& z_x, int offset,
                         Eigen::VectorXd& z) const override;
  void read_auxiliaries(ContactElement& e, const Eigen::VectorXd& z, int offset) const override;
  /// (g_N(x_n) − f_3, 0, …): the analogue of g(π_n).
  Vector6 start_residual(const ContactElement& e, const Eigen::VectorXd& x_n) const override;

  /// Face f's patch with its nodes renumbered for the element kernels (local_patch), made once.
  const TensorPatch& local_patch_of(int face) const { return local_patches_[face]; }

  /// Adds one element's rows (Rx to its 15 dofs, Rl to its multiplier row at `offset`) and, if K is
  /// given, its 16 × 16 block [Kxx Kxl; Klx 0]. Result: MidpointResult or HhtElementResult.
  /// The same for an element on a smooth patch (patch_nts_element.hpp): 3M + 3 dofs.
  void scatter_patch(const ContactElement& e, int offset, const PatchNtsResult& r, Eigen::VectorXd& R,
                     solve::BlockPattern* K) const;

  template <class Result>
  void scatter(const ContactElement& e, int offset, const Result& r, Eigen::VectorXd& R,
               solve::BlockPattern* K) const {
    const std::array<int, 15> dofs = element_dofs(slave_node(e), face_of(e));
    for (int i = 0; i < 15; ++i) R[dofs[i]] += r.Rx[i];
    R[offset] += r.Rl;
    if (!K) return;
    Eigen::Matrix<double, 16, 16> block = Eigen::Matrix<double, 16, 16>::Zero();
    block.topLeftCorner<15, 15>() = r.Kxx;
    block.topRightCorner<15, 1>() = r.Kxl;
    block.bottomLeftCorner<1, 15>() = r.Klx;
    K->scatter(e.block, block);
  }

  std::vector<TensorPatch> local_patches_;  ///< per master face, empty on the faceted surface
  /// Forces at t_{n+1} and t_n (HHT-α, generalized-α) rather than at the midpoint; fixed by the scheme,
  /// so that restore_state's replayed end_step (which carries no rule) rebuilds λ_n N_s(x_n).
  bool end_point_ = false;
  /// λ N_s of an element active at the end of the last converged step (end point).
  struct PreviousForce {
    int slave = -1;         ///< index into PairSurfaces::slave_nodes
    std::vector<int> dofs;  ///< the element's
    Eigen::VectorXd force;
  };
  std::vector<PreviousForce> previous_force_;
};

}  // namespace stoss::contact
