#pragma once
/// @file What a run builds from its model: mass, the terms the scene calls for, fixed dofs and the
/// initial state, and the frames it reports of a state.

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "core/contact/contact.hpp"
#include "core/fem/assembly.hpp"
#include "core/loads/surface_load.hpp"
#include "core/model/model.hpp"
#include "core/model/observer.hpp"
#include "core/run/supports.hpp"
#include "core/time/scheme.hpp"

namespace stoss::run {

/// Everything a run builds from the model: only the terms the scene calls for.
struct Problem {
  solve::SparseMatrix mass;
  solve::SparseMatrix velocity_map;  ///< P of docs/theory.md (4.13), empty unless a node is massless
  std::unique_ptr<fem::ElasticityTerm> elasticity;
  std::unique_ptr<fem::GravityTerm> gravity;
  std::vector<std::unique_ptr<loads::SurfaceLoad>> loads;      ///< one per scene load; none without loads
  std::vector<std::unique_ptr<contact::ContactTerm>> contact;  ///< one per pair; none without contact
  std::unique_ptr<PrescribedMotion>
      supports;  ///< the supports that move; none unless a displacement is non-zero
  std::vector<char> fixed;
  /// The held dofs of each boundary entry, a dof held by several counted in the first
  /// (series/reaction_force).
  std::vector<std::vector<int>> held_dofs;
  double total_mass = 0;
  double length_scale = 1;
  double setup_contact_seconds = 0;  ///< building the contact terms
  double setup_seconds = 0;          ///< the rest of build_problem: geometry, mass, elasticity

  /// The terms in the order the integrator gets them: elasticity, gravity if any, the loads, the moving
  /// supports if any, then the contact pairs.
  std::vector<time::Term*> terms() const;
  /// Index of the first contact term in terms().
  size_t first_contact_term() const { return (gravity ? 2 : 1) + loads.size() + (supports ? 1 : 0); }
  /// Σ of the loads' and the moving supports' work so far in each step's discrete form (docs/theory.md
  /// (5b.5), (5b.9)): series/external_work.
  double external_work() const;
  /// Σ of the loads' impulses so far, each step's in its discrete form (loads::SurfaceLoad::impulse).
  Eigen::Vector3d load_impulse() const;
  /// The gravity force on all bodies, Σ_I M_I g (0 without gravity).
  Eigen::Vector3d gravity_force() const;
  /// The force each boundary entry exerted on its body in the step whose held-dof reaction is `reaction`
  /// (Integrator::reaction; empty: 0): series/reaction_force.
  std::vector<Eigen::Vector3d> entry_reactions(const Eigen::VectorXd& reaction) const;
};

Problem build_problem(const model::Model& m);

/// The state at t = 0: reference positions, the bodies' initial velocities, zero accelerations.
time::State initial_state(const model::Model& m, const Problem& p);

/// Positions, velocities, element stresses and, with contact, the nodal contact pressure of state s.
model::Frame frame_of(const time::State& s, const Problem& p);
/// `frame` (positions, velocities and contact pressure as a checkpoint keeps them) with its stresses.
model::Frame with_stresses(model::Frame frame, const Problem& p);

}  // namespace stoss::run
