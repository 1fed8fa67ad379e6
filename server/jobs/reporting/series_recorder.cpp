#include "server/jobs/reporting/series_recorder.hpp"

#include <charconv>
#include <cmath>

namespace stoss::server::jobs {

namespace {

std::string shortest(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

/// The layout line and the rows of a partial series file (a torn last line is left out).
struct Partial {
  std::vector<model::SeriesSpec> layout;  ///< from [{"name", "components", "integer", "items"}...]
  std::vector<std::vector<double>> rows;  ///< [step, time, values...]
};

model::SeriesSpec spec_of(const nlohmann::json& s) {
  return {s.value("name", ""), s.value("components", 1), s.value("integer", false), s.value("items", 0)};
}

std::optional<Partial> load(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  Partial p;
  std::string line;
  if (!std::getline(in, line)) return std::nullopt;
  try {
    const nlohmann::json first = nlohmann::json::parse(line);
    for (const auto& s : first.at("series")) p.layout.push_back(spec_of(s));
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
    series.push_back(
        {{"name", s.name}, {"components", s.components}, {"integer", s.integer}, {"items", s.items}});
  out_ << nlohmann::json{{"series", series}}.dump() << '\n' << std::flush;
  last_flush_ = std::chrono::steady_clock::now();
  total_ = layout.index_of("total_energy");
  dissipated_ = layout.index_of("dissipated_energy");
  work_ = layout.index_of("external_work");
}

void SeriesRecorder::step(const model::StepRow& row) {
  std::string line = "[" + std::to_string(row.step) + "," + shortest(row.time);
  for (double v : row.values) line += "," + (std::isfinite(v) ? shortest(v) : std::string("null"));
  out_ << line << "]\n";
  const auto now = std::chrono::steady_clock::now();
  if (row.step <= flushed_at_once || now - last_flush_ >= std::chrono::milliseconds(flush_every_)) {
    out_.flush();
    last_flush_ = now;
  }
  if (total_ >= 0 && dissipated_ >= 0 &&
      static_cast<std::size_t>(std::max(total_, dissipated_)) < row.values.size()) {
    const double h = row.values[static_cast<std::size_t>(total_)],
                 d = row.values[static_cast<std::size_t>(dissipated_)],
                 w = work_ >= 0 ? row.values[static_cast<std::size_t>(work_)] : 0.0;  // W_ext
    if (!initial_energy_) initial_energy_ = h + d - w;
    last_dissipated_ = d;
    const double scale = std::abs(*initial_energy_) > 0 ? std::abs(*initial_energy_) : 1.0;
    balance_drift_ = std::max(balance_drift_, std::abs(h + d - w - *initial_energy_) / scale);
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

namespace {

/// Where a few series the partial summary reads sit in a row (−1: absent).
struct SummaryColumns {
  int total = -1, dissipated = -1, newton = -1, work = -1;
};

/// Each series of the partial file as the result's JSON form, and where the summary's columns sit.
nlohmann::json series_json(const Partial& p, SummaryColumns& columns) {
  nlohmann::json out = nlohmann::json::object();
  nlohmann::json step = nlohmann::json::array(), time = nlohmann::json::array();
  for (const auto& row : p.rows) {
    step.push_back(static_cast<std::int64_t>(row[0]));
    time.push_back(row.size() > 1 ? row[1] : 0.0);
  }
  out["step"] = step;
  out["time"] = time;
  std::size_t offset = 2;
  for (const model::SeriesSpec& spec : p.layout) {
    if (spec.name == "total_energy") columns.total = static_cast<int>(offset);
    if (spec.name == "dissipated_energy") columns.dissipated = static_cast<int>(offset);
    if (spec.name == "newton_iterations") columns.newton = static_cast<int>(offset);
    if (spec.name == "external_work") columns.work = static_cast<int>(offset);
    nlohmann::json values = nlohmann::json::array();
    std::vector<double> cells(static_cast<std::size_t>(spec.components));
    for (const auto& row : p.rows) {  // cells past a short row are null
      for (std::size_t c = 0; c < cells.size(); ++c)
        cells[c] = offset + c < row.size() ? row[offset + c] : std::nan("");
      values.push_back(model::row_json(spec, cells.data()));
    }
    out[spec.name] = values;
    offset += static_cast<std::size_t>(spec.components);
  }
  return out;
}

/// The energy figures of the summary up to the last recorded step, as the run's summary computes them
/// (core/run/measures.cpp): max |H_n − W_n − H_0| over |H_0|, or over max |H_n| when the run counts
/// external work (a loaded body may start at rest).
void add_energy_summary(const Partial& p, const SummaryColumns& c, nlohmann::json& summary) {
  const auto at = [](const std::vector<double>& row, int column) {
    return column >= 0 ? row[static_cast<std::size_t>(column)] : 0.0;
  };
  const double h0 = at(p.rows.front(), c.total);
  double largest = std::abs(h0);
  if (c.work >= 0)
    for (const auto& row : p.rows) largest = std::max(largest, std::abs(at(row, c.total)));
  double drift = 0, balance = 0;
  const double scale = largest > 0 ? largest : 1.0;
  for (const auto& row : p.rows) {
    const double h = at(row, c.total);
    drift = std::max(drift, std::abs(h - at(row, c.work) - h0) / scale);
    if (c.dissipated >= 0) {
      const double d0 = at(p.rows.front(), c.dissipated);
      balance = std::max(balance, std::abs(h + at(row, c.dissipated) - at(row, c.work) - h0 - d0) / scale);
    }
  }
  summary["initial_energy"] = h0;
  summary["energy_drift"] = drift;
  if (c.work >= 0) summary["external_work"] = at(p.rows.back(), c.work);
  if (c.dissipated >= 0) {
    summary["dissipated_energy"] = at(p.rows.back(), c.dissipated);
    summary["energy_plus_dissipated_drift"] = balance;
  }
}

}  // namespace

std::optional<nlohmann::json> read_partial_series(const std::filesystem::path& path) {
  const auto p = load(path);
  if (!p) return std::nullopt;
  SummaryColumns columns;
  nlohmann::json out = series_json(*p, columns);
  // The summary up to the last recorded step.
  const auto& last = p->rows.back();
  // The verdict judges a whole run (its bounds grow with the steps: docs/results.md, "Verdict"): it is made
  // when the run ends, null with no checks until then (docs/api.md, "Results": GET …/series).
  nlohmann::json summary = {{"completed", false},
                            {"steps", static_cast<int>(last[0])},
                            {"end_time", last.size() > 1 ? last[1] : 0.0},
                            {"verdict", nullptr},
                            {"checks", nlohmann::json::array()}};
  if (columns.total >= 0) add_energy_summary(*p, columns, summary);
  if (columns.newton >= 0) {
    double iterations = 0;
    for (const auto& row : p->rows) iterations += row[static_cast<std::size_t>(columns.newton)];
    summary["newton_iterations"] = static_cast<std::int64_t>(std::llround(iterations));
  }
  out["completed"] = false;
  out["summary"] = summary;
  return out;
}

std::optional<std::string> partial_series_csv(const std::filesystem::path& path,
                                              std::optional<long long> since) {
  const auto p = load(path);
  if (!p) return std::nullopt;
  std::string header = "time";
  for (const model::SeriesSpec& spec : p->layout)
    for (const std::string& column : model::csv_columns(spec)) header += "," + column;
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
