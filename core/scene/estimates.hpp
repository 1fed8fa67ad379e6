#pragma once
/// @file Rough scales of a model before it runs (docs/scene.md, "Checks before the run"): wave speeds,
/// element sizes, the Courant number, the slowest mode, contact durations and the run's wall time.
/// Order-of-magnitude numbers for warnings and the first ETA, not results.

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/model/model.hpp"

namespace stoss::scene {

/// One body's scales.
struct BodyScale {
  std::string name;
  double bar_speed = 0;           ///< c₀ = √(E/ρ) (W1)
  double dilatational_speed = 0;  ///< c_d = √(E(1−ν)/(ρ(1+ν)(1−2ν))) (W1)
  double smallest_element = 0;    ///< shortest element edge in the reference configuration
  double courant = 0;             ///< c_d · h / smallest_element (W2)
  double lowest_period = 0;  ///< T₁ ≈ 2 L_max / c₀, the free bar's first mode over the longest extent (W3)
  double mass = 0;
  Eigen::Vector3d extent = Eigen::Vector3d::Zero();  ///< bounding-box size
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  bool supported = false;  ///< a boundary condition holds one of its surfaces
};

/// A contact pair whose bodies approach at t = 0 (or fall together under gravity).
struct PairScale {
  size_t pair = 0;            ///< index in model.contact
  std::string slave, master;  ///< the pair's surfaces
  double approach_speed = 0;  ///< v₀ along the line between the bodies' centroids
  double hertz_duration = 0;  ///< t_H = 2.94 δ_max / v₀, sphere on a flat (W4)
  double wave_duration = 0;   ///< t_W = 2 L / c₀, L the slave's extent along the approach (W5)
  double duration = 0;        ///< max(t_H, t_W): the longer of the two sets the time of contact (W6)
};

struct Estimates {
  std::vector<BodyScale> bodies;  ///< in model order
  std::vector<PairScale> pairs;   ///< only pairs that approach
  size_t slave_nodes = 0;         ///< nodes of every pair's slave surface (a node in two pairs counts twice)
  double wall_seconds = 0;        ///< the run's wall time before it starts (W7)
};

Estimates estimate(const model::Model& model);

/// The estimates as docs/api.md shows them ("estimates" of POST /v1/validate and `stoss validate --json`).
nlohmann::json to_json(const Estimates& estimates);

/// The run-time estimate (W7): steps × (a E^k + b S), E the elements, S the slave nodes. a E^k covers
/// assembly and the sparse factorisation (which grows faster than E) over a step's Newton iterations, b S
/// the contact search and terms. Fitted to two runs of each shipped example with build/stoss run, on 2
/// cores at load ~10 (docs/measurements.md, "The run-time estimate"): every run within 2.7× of it.
inline constexpr double estimate_element_seconds = 3e-5;       ///< a
inline constexpr double estimate_element_exponent = 1.3;       ///< k
inline constexpr double estimate_slave_node_seconds = 1.2e-4;  ///< b

}  // namespace stoss::scene
