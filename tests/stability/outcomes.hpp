#pragma once
// Test helper for tests/stability: run a case with a scheme whose outcome is recorded, not asserted,
// and append it to <build>/stability_outcomes.md (the side-by-side table of docs/measurements.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

#include "../core/recording_observer.hpp"
#include "core/simulate.hpp"

namespace stoss::testing {

/// Runs m and describes the outcome in one line: the summary's energy and momentum drifts, the
/// penetration in face sizes (when face_size > 0), Newton iterations per step and the most substeps
/// a step needed (automatic step reduction) — or the step it failed at and why. `summary` receives
/// the summary of a completed run.
inline std::string outcome_of(const model::Model& m, double face_size, model::Summary* summary = nullptr) {
  RecordingObserver r;
  try {
    const model::Summary s = simulate(m, r);
    if (summary) *summary = s;
    const auto substeps = r.series("substeps");
    char penetration[64] = "";
    if (face_size > 0)
      std::snprintf(penetration, sizeof penetration, ", penetration %.2e faces",
                    s.max_penetration / face_size);
    char text[240];
    std::snprintf(text, sizeof text,
                  "completed; energy %.2e, momentum %.2e%s, %.1f Newton its/step, max substeps %.0f",
                  s.energy_drift, std::max(s.linear_momentum_drift, s.angular_momentum_drift), penetration,
                  s.newton_iterations_per_step, *std::max_element(substeps.begin(), substeps.end()));
    return text;
  } catch (const std::exception& e) {
    return "failed at step " + std::to_string(r.rows.size()) + ": " + std::string(e.what()).substr(0, 80);
  }
}

/// Appends "| case | scheme | outcome |" to <build>/stability_outcomes.md, records it as a test property
/// and prints it. Returns false if the file could not be written.
inline bool record_outcome(const std::string& name, model::Scheme scheme, const std::string& outcome) {
  std::ofstream report(std::string(STOSS_BINARY_DIR) + "/stability_outcomes.md", std::ios::app);
  report << "| " << name << " | " << model::to_string(scheme) << " | " << outcome << " |\n";
  ::testing::Test::RecordProperty(model::to_string(scheme), outcome);
  std::printf("%s / %s: %s\n", name.c_str(), model::to_string(scheme).c_str(), outcome.c_str());
  return report.good();
}

}  // namespace stoss::testing
