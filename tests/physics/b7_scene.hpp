#pragma once
// Test helper: the B7 scene of docs/theory.md §6.3, shared by the impact, HHT-contact and friction tests.
#include "core/mesh/generators.hpp"
#include "core/model/model.hpp"

namespace stoss::testing {

/// §6.3 B7: a tumbling hex8 cube (side 0.6, E = 200) over a free hex8 plate (2 × 2 × 0.4, E = 300),
/// 4 slave nodes on one master face, no gravity, no supports; h = 0.01, 150 steps. The pair's slave
/// and master are set to cube/bottom and plate/top; its other settings are the caller's.
inline model::Model b7_cube_on_free_plate(model::Scheme scheme, model::ContactPair pair, double tolerance) {
  model::Model m;
  m.mesh.add_body("plate", mesh::box({-1, -1, -0.4}, {1, 1, 0}, {1, 1, 1}));
  m.mesh.add_body("cube", mesh::box({-0.3, -0.3, 0.2}, {0.3, 0.3, 0.8}, {1, 1, 1}));
  model::BodySpec plate, cube;
  plate.name = "plate";
  plate.material = {"saint_venant_kirchhoff", 300, 0.3, 1};
  cube.name = "cube";
  cube.material = {"saint_venant_kirchhoff", 200, 0.3, 1};
  cube.initial_velocity = {0.3, 0.1, -1.0};
  cube.initial_angular_velocity = {0.6, -0.9, 0.4};
  cube.center = Eigen::Vector3d(0, 0, 0.5);
  m.bodies = {plate, cube};
  pair.slave = "cube/bottom";
  pair.master = "plate/top";
  m.contact = {pair};
  m.time = {scheme, 0.01, 1.5};
  m.solver.tolerance = tolerance;
  m.output.every = 50;
  m.effects = model::resolve_effects(m);
  return m;
}

}  // namespace stoss::testing
