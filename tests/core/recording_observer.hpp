#pragma once
// Test helper: keeps every series row and frame of a run in memory.
#include <map>
#include <string>
#include <vector>

#include "core/model/observer.hpp"

namespace stoss::testing {

class RecordingObserver : public model::Observer {
 public:
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

  model::SeriesLayout layout;
  std::vector<model::StepRow> rows;
  std::vector<model::Frame> frames;
  std::vector<std::string> logs;
  model::Summary summary;
};

}  // namespace stoss::testing
