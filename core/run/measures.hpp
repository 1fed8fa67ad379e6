#pragma once
/// @file What a run measures at the end of a step, for the series (series_table.hpp) and the summary:
/// energies and momenta, and the contact report summed over the pairs.

#include <Eigen/Core>

#include "core/model/observer.hpp"
#include "core/run/problem.hpp"
#include "core/time/integrator.hpp"

namespace stoss::run {

/// Energies and momenta (1.10)–(1.11) of a state; `contact` is the penalty energy Σ W_N + W_T (5.1),
/// `dissipated` the Coulomb work D so far (§5.2 item 7).
struct Balance {
  double kinetic = 0, strain = 0, potential = 0, contact = 0, dissipated = 0;
  double external_work = 0;  ///< W: the loads' work since t_0 (docs/theory.md (5b.5)); not part of H
  Eigen::Vector3d linear = Eigen::Vector3d::Zero(), angular = Eigen::Vector3d::Zero();
  double momentum_scale = 0, angular_scale = 0;  ///< Σ|p_I|, Σ|x_I||p_I|: scales for relative drifts
  double total() const { return kinetic + strain + potential + contact; }  // H of (5.4)
};

Balance balance(const Problem& p, const time::State& s);

/// The contact series of one step (docs/results.md), summed or maximised over the pairs.
struct ContactRow {
  int active = 0, slipping = 0, switches = 0, unprojected = 0;
  double max_penetration = 0, own_face_penetration = 0, faceted_penetration = 0, energy_jump = 0;
};

/// The pairs' reports of the last (sub)step; with `integrator`, the energy its velocity correction restored.
ContactRow contact_row(const Problem& p, const time::Integrator* integrator);

/// Folds the contact row of one substep into the step's: the last active count, the worst
/// penetrations, the sum of the jumps.
void add_substep(ContactRow& step, const ContactRow& sub);

/// Folds a step into the summary's maxima: the drifts against the initial balance b0, the penetrations.
void update_summary(model::Summary& sum, const Balance& b0, const Balance& b, const ContactRow& c);

/// The external impulse of one step on all bodies: the loads' (their impulse's growth), gravity's h·G and
/// the supports' h·Σ R (the step's reactions, impulse-consistent over substeps).
struct StepImpulse {
  Eigen::Vector3d loads = Eigen::Vector3d::Zero(), gravity = Eigen::Vector3d::Zero(),
                  supports = Eigen::Vector3d::Zero();
};

/// Folds a step into the summary's impulse balance (docs/results.md (V10)): |p_n − p_{n−1} − J_n| over the
/// larger of the momenta's magnitudes Σ|p_I| and |J_loads| + |h G| + |h R|.
void update_impulse_balance(model::Summary& sum, const Balance& before, const Balance& after,
                            const StepImpulse& impulse);

}  // namespace stoss::run
