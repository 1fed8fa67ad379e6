#pragma once
/// @file Frictional penalty contact of one slave node against one smooth master patch over one step
/// (docs/theory.md §5.2 on the patch geometry of docs/smooth_master_surface.md §3.8): the law and
/// return map of penalty_law.hpp with the patch's variations, so that the gap and the tangent plane a
/// node sees stay continuous when it moves from one face's patch to the next.
///
/// Element vector [x_s; y_0 … y_{M−1}] (3M + 3 entries) on a local patch whose node K is entry K + 1
/// (local_patch, local_positions in elements/patch_nts_element.hpp). Tangent analytic, with the third
/// derivatives of the patch in Σ_α t_α ∂D_α; checked against central differences in
/// tests/core/contact/penalty/test_patch_penalty_element.cpp.

#include <Eigen/Core>

#include "core/contact/geometry/tensor_patch.hpp"
#include "core/contact/penalty/penalty_law.hpp"

namespace stoss::contact {

/// One element of a smooth patch.
using PatchPenaltyResult = PenaltyResultT<Eigen::Dynamic>;

/// The element of §5.2 on `local` for the step x_n → x_{n+1}: CPPs at x_n, x_m, x_{n+1} (all from
/// `xi_start`, on the patch extended beyond its face), normal traction per `p.normal_rule`, history
/// transport, return map (5.3), force (5.2) at x_m and its tangent w.r.t. x_{n+1}. `face_size` scales
/// the "dd" rule's degenerate-step test.
PatchPenaltyResult patch_penalty_element(const TensorPatch& local, const Eigen::VectorXd& x_n,
                                         const Eigen::VectorXd& x_1, const FrictionHistory& history,
                                         const PenaltyParameters& p, const Eigen::Vector2d& xi_start,
                                         double face_size);

}  // namespace stoss::contact
