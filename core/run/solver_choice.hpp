#pragma once
/// @file The solvers of a run, from the scene's solver settings: which linear solver (solver.linear),
/// Newton's options, and the log lines that say what was chosen and how it went.

#include <string>

#include "core/model/model.hpp"
#include "core/model/observer.hpp"
#include "core/solve/linear_solver.hpp"
#include "core/solve/newton.hpp"

namespace stoss::run {

/// The linear solver named by solver.linear; auto picks petsc_gamg from auto_iterative_elements(m) elements
/// on, where it overtakes the LU (docs/measurements.md, "Linear solvers"), direct below.
solve::LinearMethod linear_method(const model::Model& m);

/// Where auto switches to petsc_gamg: model::SolverSpec's threshold for scenes with or without contact.
int auto_iterative_elements(const model::Model& m);

/// The log line naming the linear solver of the run (and why, for auto).
std::string linear_solver_line(const model::Model& m);

/// The log's line on the Krylov solves of a run (none with the direct solver).
std::string krylov_line(const solve::LinearSolver& linear);

/// Newton from the scene's solver settings.
solve::NewtonOptions newton_options(const model::Model& m);

/// The summary's Krylov figures of the run's linear solver, and the log's lines on them.
void report_linear_solver(const solve::LinearSolver& linear, model::Summary& summary,
                          model::Observer& observer);

}  // namespace stoss::run
