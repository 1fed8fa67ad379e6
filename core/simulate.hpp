#pragma once
/// @file The one entry point of the core: run a model, report to an observer, stop when asked.

#include <atomic>
#include <stdexcept>
#include <string>

#include "core/model/model.hpp"
#include "core/model/observer.hpp"

namespace stoss {

/// Set from any thread to stop a run at the end of the current time step.
using CancelFlag = std::atomic<bool>;

/// A step that cannot be solved: names the step, the time and the residual history.
class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Runs `model` from t = 0 to model.time.end. Throws SolverError when a step fails
/// (after observer.end with completed = false). Returns with completed = false when canceled.
model::Summary simulate(const model::Model& model, model::Observer& observer, const CancelFlag* cancel = nullptr);

}  // namespace stoss
