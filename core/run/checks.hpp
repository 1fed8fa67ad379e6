#pragma once
/// @file The verdict of a run: named checks of its summary against the bounds the scheme and the scene
/// promise (docs/results.md, "Verdict"), and "ok" or "suspect".

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/model/model.hpp"
#include "core/model/observer.hpp"

namespace stoss::run {

/// Whether the model's momenta are conserved: no boundary condition, no load and no gravity, so no body is
/// held and no external force acts (contact between free bodies is internal).
bool is_free(const model::Model& m);

/// The bound of (V6) newton_iterations_per_step (docs/results.md, "Verdict"): 0.6 · solver.max_iterations,
/// plus 2 log₁₀(n_dof / 1000) above 1000 dofs and 2 log₂(1 + n_c / 100) for n_c contact slave nodes.
double newton_bound(const model::Model& m);

/// How far inside an element a node must lie to count as inside it: every |ξ| ≤ 1 − this (docs/results.md,
/// "Verdict", (V9)). 0.05 is a depth of 2.5 % of the element across that face: twenty times the
/// contact's own tolerated penetration (0.29 % of a face at the default penalty, docs/scene.md), far
/// above round-off, so a node resting on a face or pressed into it by a penalty is not inside.
inline constexpr double inside_margin = 0.05;

/// Nodes of one body inside a deformed hex8 of another body at positions x (3 per node; docs/results.md,
/// "Verdict", (V9)): element bounding boxes first, then the trilinear map inverted by Newton.
int nodes_inside_other_body(const mesh::Mesh& mesh, const Eigen::VectorXd& x);

/// The checks of a run's summary (docs/results.md, "Verdict"), in a fixed order.
std::vector<model::Check> run_checks(const model::Model& m, const model::Summary& s);
/// The same, plus (V9) `nodes_inside_other_body` on the final positions x when the scene has two bodies.
std::vector<model::Check> run_checks(const model::Model& m, const model::Summary& s,
                                     const Eigen::VectorXd& x);

/// "ok" when every check passed, else "suspect".
std::string verdict_of(const std::vector<model::Check>& checks);

/// Fills s.checks and s.verdict.
void add_verdict(const model::Model& m, model::Summary& s);
/// Fills s.checks and s.verdict with the checks of the final positions x as well.
void add_verdict(const model::Model& m, model::Summary& s, const Eigen::VectorXd& x);

}  // namespace stoss::run
