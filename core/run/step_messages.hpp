#pragma once
/// @file The log's and the error's words for a step that could not be solved (docs/command_line.md).

#include <string>

#include "core/run/step_control.hpp"
#include "core/time/step_reduction.hpp"

namespace stoss::run {

/// A time as the messages print it (6 significant digits).
std::string time_text(double t);

/// The message of a fixed step (step index `step`, from t over h) whose Newton solves failed after every
/// halving.
std::string failure_message(int step, double t, double h, const time::ReducedStep& r);

/// The message of a run whose step controller would need a step below time.min_step, naming the contact
/// pair and the nodes that forced it.
std::string below_min_step_message(int step, double t, double h, const std::string& reason,
                                   const ContactEvents& events, double min_step);

}  // namespace stoss::run
