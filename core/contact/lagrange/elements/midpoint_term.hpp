#pragma once
/// @file Frictionless Lagrange NTS contact for the implicit midpoint rule (docs/theory.md §4.2, seed
/// eqs 50–52): one multiplier per active element after x_{n+1} in z.

#include <array>
#include <vector>

#include "core/contact/lagrange/lagrange_term.hpp"
#include "core/contact/lagrange/elements/patch_nts_element.hpp"
#include "core/contact/geometry/surface.hpp"

namespace stoss::contact {

/// The contact term of the midpoint scheme: h λ N_s(x_m) in the momentum rows, g_N(x_{n+1}) − f_3 = 0.
/// Conserves both momenta, not energy (§4.2). HhtContactTerm reuses its multiplier bookkeeping.
/// @note Measures: the constraint row is divided by the face size; the multiplier increment is not
///       measured (the rows it enters are).
class MidpointContactTerm : public LagrangeContactTerm {
 public:
  MidpointContactTerm(const mesh::Mesh& mesh, const model::ContactPair& pair);
  void add(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
           solve::BlockPattern* K) const override;
  double auxiliary_residual_measure(const Eigen::VectorXd& R, const time::MeasureScales& s) const override;

 protected:
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

 private:
  std::vector<TensorPatch> local_patches_;  ///< per master face, empty on the faceted surface
};

}  // namespace stoss::contact
