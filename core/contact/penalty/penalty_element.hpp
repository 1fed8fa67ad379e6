#pragma once
/// @file Frictional penalty contact of one NTS element: one slave node against one 4-node master
/// segment over one time step n → n+1 (docs/theory.md §5, (5.1)–(5.4)).
///
/// Pure functions: the friction history goes in, the updated history comes out (`history_after`),
/// to be committed by the caller only when the step has converged (§5.2 item 7). The master face is
/// the one assigned for the step (§3.4); this element does not test whether ξ lies on the face.
///
/// Tangent: analytic (no finite differences). ∂D_α/∂x, the second derivative of the CPP that
/// (5.2) needs, is the derivative of (3.7) at fixed traction, built from (3.4), (3.8) and (3.9);
/// everything is fixed-size, no heap allocation. Checked against central differences in
/// tests/core/contact/penalty/test_penalty_element.cpp.

#include <Eigen/Core>

#include "core/contact/geometry/projection.hpp"
#include "core/contact/penalty/penalty_law.hpp"
#include "core/contact/types.hpp"

namespace stoss::contact {

/// One element of a bilinear face: element vector [x_s; y_1; y_2; y_3; y_4].
using PenaltyResult = PenaltyResultT<15>;

/// Default penalty stiffness ε_N = ε_T = 10 E ℓ [choice] (§5.1): E the Young's modulus, ℓ the mean
/// master face size; units of force/length. Check that penetration stays below 1 % of ℓ.
double penalty_default_stiffness(double youngs_modulus, double face_size);

/// The element of §5.2 for the step x_n → x_{n+1} with friction history `history`: CPPs at x_n,
/// x_m, x_{n+1} (all from `xi_start`), normal traction per `p.normal_rule`, history transport,
/// trial and return map (5.3), force (5.2) at x_m and its analytic tangent w.r.t. x_{n+1}.
PenaltyResult penalty_element(const Vector15& x_n, const Vector15& x_1, const FrictionHistory& history,
                              const PenaltyParameters& p, const Eigen::Vector2d& xi_start);

}  // namespace stoss::contact
