#pragma once
/// @file The convergence scale of static load steps (docs/theory.md §5b.6): a force in place of the
/// dynamic schemes' momentum floor.

#include "core/model/model.hpp"
#include "core/run/problem.hpp"

namespace stoss::run {

/// F of a static scene (docs/theory.md (5b.7a)): the weight, each load at its largest amplitude over its
/// reference area, and each prescribed motion as the force E A |u| / ℓ that stretches its body by it (ℓ =
/// `length`); 0 for none.
double static_force_scale(const model::Model& m, double total_mass, double length);

/// The mass the integrator's residual floor 1e-4 m ℓ / h is given: the problem's total mass for a dynamic
/// scheme; for static steps the m that makes the floor h F at h = time.step (5b.7), so that a step whose
/// load does not change (the predictor already solves it) is measured against the load it carries.
double convergence_mass(const model::Model& m, const Problem& p);

}  // namespace stoss::run
