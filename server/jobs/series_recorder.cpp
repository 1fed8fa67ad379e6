#include "server/jobs/series_recorder.hpp"

#include <charconv>
#include <cmath>

namespace stoss::server::jobs {

namespace {

int offset_of(const model::SeriesLayout& layout, const std::string& name) {
  int offset = 0;
  for (const auto& s : layout.series) {
    if (s.name == name) return offset;
    offset += s.components;
  }
  return -1;
}

std::string shortest(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

/// The layout line and the rows of a partial series file (a torn last line is left out).
struct Partial {
  nlohmann::json layout;                       ///< [{"name", "components", "integer"}...]
  std::vector<std::vector<double>> rows;       ///< [step, time, values...]
};

std::optional<Partial> load(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  Partial p;
  std::string line;
  if (!std::getline(in, line)) return std::nullopt;
  try {
    p.layout = nlohmann::json::parse(line).at("series");
  } catch (const std::exception&) {
    return std::nullopt;
  }
  while (std::getline(in, line)) {
    try {
      const auto cells = nlohmann::json::parse(line);
      std::vector<double> row;
      for (const auto& cell : cells) row.push_back(cell.is_number() ? cell.get<double>() : std::nan(""));
      if (row.size() < 2) break;
      p.rows.push_back(std::move(row));
    } catch (const std::exception&) {
      break;  // the line being written
    }
  }
  if (p.rows.empty()) return std::nullopt;
  return p;
}

}  // namespace

SeriesRecorder::SeriesRecorder(const std::filesystem::path& path, Millis flush_every)
    : out_(path, std::ios::trunc), flush_every_(flush_every) {}

void SeriesRecorder::begin(const model::Model&, const model::SeriesLayout& layout) {
  nlohmann::json series = nlohmann::json::array();
  for (const auto& s : layout.series)
    series.push_back({{"name", s.name}, {"components", s.components}, {"integer", s.integer}});
  out_ << nlohmann::json{{"series", series}}.dump() << '\n' << std::flush;
  last_flush_ = std::chrono::steady_clock::now();
  total_ = offset_of(layout, "total_energy");
  dissipated_ = offset_of(layout, "dissipated_energy");
}

void SeriesRecorder::step(const model::StepRow& row) {
  std::string line = "[" + std::to_string(row.step) + "," + shortest(row.time);
  for (double v : row.values) line += "," + (std::isfinite(v) ? shortest(v) : std::string("null"));
  out_ << line << "]\n";
  const auto now = std::chrono::steady_clock::now();
  if (now - last_flush_ >= std::chrono::milliseconds(flush_every_)) {
    out_.flush();
    last_flush_ = now;
  }
  if (total_ >= 0 && dissipated_ >= 0 && static_cast<std::size_t>(std::max(total_, dissipated_)) < row.values.size()) {
    const double h = row.values[static_cast<std::size_t>(total_)], d = row.values[static_cast<std::size_t>(dissipated_)];
    if (!initial_energy_) initial_energy_ = h + d;
    last_dissipated_ = d;
    const double scale = std::abs(*initial_energy_) > 0 ? std::abs(*initial_energy_) : 1.0;
    balance_drift_ = std::max(balance_drift_, std::abs(h + d - *initial_energy_) / scale);
  }
}

void SeriesRecorder::end(const model::Summary& summary) {
  out_.flush();
  summary_ = summary;
}

std::optional<double> SeriesRecorder::dissipated_energy() const {
  return last_dissipated_;
}

std::optional<double> SeriesRecorder::energy_plus_dissipated_drift() const {
  if (!last_dissipated_) return std::nullopt;
  return balance_drift_;
}

std::optional<nlohmann::json> read_partial_series(const std::filesystem::path& path) {
  const auto p = load(path);
  if (!p) return std::nullopt;
  nlohmann::json out = nlohmann::json::object();
  nlohmann::json step = nlohmann::json::array(), time = nlohmann::json::array();
  for (const auto& row : p->rows) {
    step.push_back(static_cast<std::int64_t>(row[0]));
    time.push_back(row.size() > 1 ? row[1] : 0.0);
  }
  out["step"] = step;
  out["time"] = time;
  std::size_t offset = 2;
  int total = -1, dissipated = -1, newton = -1;
  for (const auto& s : p->layout) {
    const std::string name = s.value("name", "");
    const std::size_t components = s.value("components", 1);
    const bool integer = s.value("integer", false);
    if (name == "total_energy") total = static_cast<int>(offset);
    if (name == "dissipated_energy") dissipated = static_cast<int>(offset);
    if (name == "newton_iterations") newton = static_cast<int>(offset);
    nlohmann::json values = nlohmann::json::array();
    for (const auto& row : p->rows) {
      auto cell = [&](std::size_t c) -> nlohmann::json {
        if (offset + c >= row.size()) return nullptr;
        const double v = row[offset + c];
        return integer ? nlohmann::json(static_cast<std::int64_t>(std::llround(v))) : nlohmann::json(v);
      };
      if (components == 1) {
        values.push_back(cell(0));
      } else {
        nlohmann::json r = nlohmann::json::array();
        for (std::size_t c = 0; c < components; ++c) r.push_back(cell(c));
        values.push_back(r);
      }
    }
    out[name] = values;
    offset += components;
  }
  // The summary up to the last recorded step.
  const auto& last = p->rows.back();
  nlohmann::json summary = {{"completed", false},
                            {"steps", static_cast<int>(last[0])},
                            {"end_time", last.size() > 1 ? last[1] : 0.0}};
  if (total >= 0) {
    const double h0 = p->rows.front()[static_cast<std::size_t>(total)];
    double drift = 0, balance = 0;
    const double scale = std::abs(h0) > 0 ? std::abs(h0) : 1.0;
    for (const auto& row : p->rows) {
      const double h = row[static_cast<std::size_t>(total)];
      drift = std::max(drift, std::abs(h - h0) / scale);
      if (dissipated >= 0) {
        const double d0 = p->rows.front()[static_cast<std::size_t>(dissipated)];
        balance = std::max(balance, std::abs(h + row[static_cast<std::size_t>(dissipated)] - h0 - d0) / scale);
      }
    }
    summary["initial_energy"] = h0;
    summary["energy_drift"] = drift;
    if (dissipated >= 0) {
      summary["dissipated_energy"] = last[static_cast<std::size_t>(dissipated)];
      summary["energy_plus_dissipated_drift"] = balance;
    }
  }
  if (newton >= 0) {
    double iterations = 0;
    for (const auto& row : p->rows) iterations += row[static_cast<std::size_t>(newton)];
    summary["newton_iterations"] = static_cast<std::int64_t>(std::llround(iterations));
  }
  out["completed"] = false;
  out["summary"] = summary;
  return out;
}

std::optional<std::string> partial_series_csv(const std::filesystem::path& path, std::optional<long long> since) {
  const auto p = load(path);
  if (!p) return std::nullopt;
  std::string header = "time";
  for (const auto& s : p->layout) {
    const std::string name = s.value("name", "");
    const int components = s.value("components", 1);
    if (components == 1) header += "," + name;
    else if (components == 3) header += "," + name + "_x," + name + "_y," + name + "_z";
    else
      for (int c = 0; c < components; ++c) header += "," + name + "_" + std::to_string(c);
  }
  std::string out = header + "\n";
  for (const auto& row : p->rows) {
    if (since && row[0] <= static_cast<double>(*since)) continue;
    std::string line = shortest(row.size() > 1 ? row[1] : 0.0);
    for (std::size_t i = 2; i < row.size(); ++i) line += "," + shortest(row[i]);
    out += line + "\n";
  }
  return out;
}

nlohmann::json series_after(nlohmann::json series, std::optional<long long> since) {
  const std::size_t rows = series.value("time", nlohmann::json::array()).size();
  if (!series.contains("step")) {
    nlohmann::json step = nlohmann::json::array();
    for (std::size_t i = 0; i < rows; ++i) step.push_back(static_cast<std::int64_t>(i));
    series["step"] = step;
  }
  if (!since) return series;
  std::size_t skipped = 0;  // steps ascend: the rows to drop come first
  while (skipped < rows && series["step"][skipped].get<long long>() <= *since) ++skipped;
  for (auto& [name, values] : series.items())
    if (values.is_array() && values.size() == rows)
      values.erase(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(skipped));
  return series;
}

std::string csv_rows_after(const std::string& csv, std::optional<long long> since) {
  if (!since) return csv;
  std::size_t end_of_header = csv.find('\n');
  if (end_of_header == std::string::npos) return csv;
  std::size_t cut = end_of_header + 1;
  for (long long step = 0; step <= *since && cut < csv.size(); ++step) {
    const std::size_t end_of_line = csv.find('\n', cut);
    cut = end_of_line == std::string::npos ? csv.size() : end_of_line + 1;
  }
  return csv.substr(0, end_of_header + 1) + csv.substr(cut);
}

}  // namespace stoss::server::jobs
