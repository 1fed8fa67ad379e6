#pragma once
/// @file The verdict of a run: named checks of its summary against the bounds the scheme and the scene
/// promise (docs/results.md, "Verdict"), and "ok" or "suspect".

#include <string>
#include <vector>

#include "core/model/model.hpp"
#include "core/model/observer.hpp"

namespace stoss::run {

/// Whether the model's momenta are conserved: no boundary condition, no load and no gravity, so no body is held
/// and no external force acts (contact between free bodies is internal).
bool is_free(const model::Model& m);

/// The checks of a run's summary (docs/results.md, "Verdict"), in a fixed order.
std::vector<model::Check> run_checks(const model::Model& m, const model::Summary& s);

/// "ok" when every check passed, else "suspect".
std::string verdict_of(const std::vector<model::Check>& checks);

/// Fills s.checks and s.verdict.
void add_verdict(const model::Model& m, model::Summary& s);

}  // namespace stoss::run
