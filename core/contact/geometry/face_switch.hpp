#pragma once
/// @file The face-switch rule of NTS contact (docs/theory.md §3.4), in one place for every contact term.
///
/// At the start of each step a slave node whose converged ξ left its master face by more than the
/// hysteresis ε_sw (`|ξ|∞ > 1 + ε_sw`) looks for the face that accepts its position x_n (best_face in
/// assignment.hpp); if none does, it stays on its face, whose projection extends consistently. On a
/// switch the gap the node carries is chosen by `switch_gap`:
///   - keep: the constraint keeps the gap the node had (no energy jump, the node may stay below its new
///     face until it separates);
///   - clamp: the new face's true gap from now on, never freezing a penetration (a small energy jump,
///     reported as `contact_energy_jump`).
/// Lagrange terms express it as the gap target f_3 of their constraint, penalty terms as an offset of
/// the gap their penalty law sees.

#include <Eigen/Core>

#include "core/model/model.hpp"

namespace stoss::contact {

/// Whether a node last at ξ must look for another face: |ξ|∞ > 1 + ε_sw.
inline bool leaves_face(const Eigen::Vector2d& xi, double hysteresis) {
  return xi.cwiseAbs().maxCoeff() > 1 + hysteresis;  // §3.4 hysteresis ε_sw
}

/// Lagrange: the gap target f_3 on the new face, whose true gap at x_n is `new_gap`; `target` is the
/// target on the old face. keep: the new gap. clamp: with impact persist, the new gap clamped to
/// [0, target] (a penetration is never frozen in), with located too; else 0.
double switched_gap_target(model::SwitchGap rule, model::ImpactMode impact, double new_gap, double target);

/// Penalty: the offset subtracted from the new face's gap so that the penalty law continues with the
/// gap `kept` it saw on the old face. keep: new_gap − kept while penetrating (kept < 0), else the part
/// of a penetration the new face would add (min(new_gap, 0)). clamp: 0.
double switched_gap_offset(model::SwitchGap rule, double kept, double new_gap);

}  // namespace stoss::contact
