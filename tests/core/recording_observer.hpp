#pragma once
// Test helper: keeps every series row and frame of a run in memory.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/model/observer.hpp"

namespace stoss::testing {

class RecordingObserver : public model::Observer {
 public:
  /// Set by a test binary whose every run must end with the verdict "ok" (tests/physics/verdict_ok.cpp,
  /// docs/results.md "Verdict"): a suspect run fails the test that made it, unless it allow_suspect()s.
  static inline bool require_ok_verdict = false;
  RecordingObserver() = default;
  RecordingObserver(const RecordingObserver&) = default;
  RecordingObserver& operator=(const RecordingObserver&) = default;
  ~RecordingObserver() override {
    if (require_ok_verdict && !suspect_allowed_ && summary.verdict == "suspect")
      ADD_FAILURE() << "the run ended suspect; its checks: " << failed_checks();
  }
  /// For a run meant to break a check (a comparator, a mistake shown on purpose).
  void allow_suspect() { suspect_allowed_ = true; }
  /// "name value > bound; " for each failed check of the run.
  std::string failed_checks() const {
    std::string out;
    for (const model::Check& c : summary.checks)
      if (!c.passed) out += c.name + " " + std::to_string(c.value) + " > " + std::to_string(c.bound) + "; ";
    return out;
  }

  void begin(const model::Model&, const model::SeriesLayout& l) override { layout = l; }
  void step(const model::StepRow& r) override { rows.push_back(r); }
  void frame(const model::Frame& f) override { frames.push_back(f); }
  void log(const std::string& line) override { logs.push_back(line); }
  void end(const model::Summary& s) override { summary = s; }

  /// Component k of series `name` at every recorded step.
  std::vector<double> series(const std::string& name, int k = 0) const {
    const int at = layout.index_of(name);
    std::vector<double> out;
    if (at < 0) return out;
    for (const auto& r : rows) out.push_back(r.values[at + k]);
    return out;
  }
  bool has_series(const std::string& name) const { return layout.index_of(name) >= 0; }

  /// max_n |s_n − s_{n−1}| / |s_0| of the scalar series `name` (the largest change in a step of an energy).
  double largest_step_change(const std::string& name) const {
    const std::vector<double> s = series(name);
    double worst = 0;
    for (size_t n = 1; n < s.size(); ++n) worst = std::max(worst, std::abs(s[n] - s[n - 1]) / std::abs(s[0]));
    return worst;
  }

  /// max_n |v_n − v_0| / |v_0| of the 3-vector series `name` (a momentum).
  double vector_drift(const std::string& name) const {
    const std::vector<double> x = series(name, 0), y = series(name, 1), z = series(name, 2);
    const Eigen::Vector3d first(x.front(), y.front(), z.front());
    double worst = 0;
    for (size_t n = 0; n < x.size(); ++n)
      worst = std::max(worst, (Eigen::Vector3d(x[n], y[n], z[n]) - first).norm() / first.norm());
    return worst;
  }

  /// Whether every value of every recorded row is finite (no NaN, no inf).
  bool all_finite() const {
    for (const auto& row : rows)
      for (double v : row.values)
        if (!std::isfinite(v)) return false;
    return true;
  }

  /// Times of the first and last step with active contacts, {-1, -1} if none.
  std::pair<double, double> contact_window() const {
    const std::vector<double> active = series("active_contacts");
    std::pair<double, double> window{-1, -1};
    for (size_t n = 0; n < active.size(); ++n)
      if (active[n] > 0) {
        if (window.first < 0) window.first = rows[n].time;
        window.second = rows[n].time;
      }
    return window;
  }

  model::SeriesLayout layout;
  std::vector<model::StepRow> rows;
  std::vector<model::Frame> frames;
  std::vector<std::string> logs;
  model::Summary summary;

 private:
  bool suspect_allowed_ = false;
};

/// max_n |s_n − s_0| / scale over every step.
inline double max_drift(const std::vector<double>& s, double scale) {
  double worst = 0;
  for (double v : s) worst = std::max(worst, std::abs(v - s.front()) / scale);
  return worst;
}

}  // namespace stoss::testing
