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

/// The run-time estimate (W7), docs/scene.md: t₀ + steps × (a E^k (1 + c log₁₀(1 + C)) + b S_f) seconds,
/// E the elements, C the largest Courant number (a larger step takes more Newton iterations), S_f the
/// slave nodes of all pairs with a frictional pair's counted twice (its stick/slip states add passes).
/// a E^k covers assembly and the sparse factorisation over a step's Newton iterations, b S_f the contact
/// search and terms, t₀ the process's setup. Fitted (least worst ratio) to the CPU seconds (user + sys,
/// the wall time of a run on an idle core) of every shipped example, measured with
///   /usr/bin/time -f "%e %U %S" build/stoss run api/examples/NAME.json -o DIR
/// on 2026-12-02 (docs/results.md, "The run-time estimate"): every example within 2.5× of it.
inline constexpr double estimate_setup_seconds = 0.05;         ///< t₀
inline constexpr double estimate_element_seconds = 1e-5;       ///< a
inline constexpr double estimate_element_exponent = 1.1;       ///< k
inline constexpr double estimate_courant_factor = 2;           ///< c
inline constexpr double estimate_slave_node_seconds = 1.7e-4;  ///< b
/// How many times S_f counts a mortar pair's slave nodes: the seed example with mortar took 6.6 s of CPU
/// against 3.2 s with node-to-segment (medians of 5, alternating), 3.4 s more over 100 steps and 218 slave
/// nodes, 0.9 b per slave node and step (docs/results.md, "The run-time estimate").
inline constexpr double estimate_mortar_weight = 1.9;

/// (W7) from its inputs: steps, elements E, the largest Courant number C and the weighted slave nodes S_f.
double run_seconds(double steps, double elements, double courant, double weighted_slave_nodes);

}  // namespace stoss::scene
