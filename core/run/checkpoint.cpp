#include "core/run/checkpoint.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <system_error>

#include "core/output/durable_file.hpp"
#include "core/output/h5.hpp"

namespace stoss::run {

namespace fs = std::filesystem;
namespace h5 = output::h5;
using output::rename_durably;
using output::sync_to_disk;

namespace {

void write_reals(const h5::File& file, const std::string& name, const double* data, hsize_t rows,
                 hsize_t columns = 0) {
  const h5::Dims dims = columns > 0 ? h5::Dims{rows, columns} : h5::Dims{rows};
  file.write_dataset(name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dims, data);
}

void write_integers(const h5::File& file, const std::string& name, const std::vector<std::int64_t>& values) {
  file.write_dataset(name, H5T_STD_I64LE, H5T_NATIVE_INT64, {values.size()}, values.data());
}

std::vector<std::int64_t> read_integers(const h5::File& file, const std::string& name) {
  std::vector<std::int64_t> out;
  for (double v : file.read_doubles(name)) out.push_back(static_cast<std::int64_t>(std::llround(v)));
  return out;
}

Eigen::VectorXd read_vector(const h5::File& file, const std::string& name) {
  const std::vector<double> values = file.read_doubles(name);
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

/// The run's accumulators as root attributes summary_<name>.
struct SummaryField {
  const char* name;
  double model::Summary::*value;
};
constexpr SummaryField summary_fields[] = {
    {"initial_energy", &model::Summary::initial_energy},
    {"energy_drift", &model::Summary::energy_drift},
    {"linear_momentum_drift", &model::Summary::linear_momentum_drift},
    {"angular_momentum_drift", &model::Summary::angular_momentum_drift},
    {"max_penetration", &model::Summary::max_penetration},
    {"max_own_face_penetration", &model::Summary::max_own_face_penetration},
    {"max_faceted_penetration", &model::Summary::max_faceted_penetration},
    {"energy_balance_error", &model::Summary::energy_balance_error},
    {"energy_balance_rise", &model::Summary::energy_balance_rise},
    {"max_abs_energy", &model::Summary::max_abs_energy},
    {"contact_energy_jumps", &model::Summary::contact_energy_jumps},
    {"impulse_balance_error", &model::Summary::impulse_balance_error},
};

void write_summary(const h5::File& file, const model::Summary& summary) {
  for (const SummaryField& f : summary_fields)
    file.write_attribute("/", std::string("summary_") + f.name, summary.*f.value);
  file.write_attribute("/", "summary_newton_iterations", summary.newton_iterations);
  file.write_attribute("/", "summary_reduced_steps", summary.reduced_steps);
}

model::Summary read_summary(const h5::File& file) {
  model::Summary summary;
  // A checkpoint written before the verdict's accumulators existed lacks them: they then count from the
  // resumed step on, rather than refusing to resume a job queued before an upgrade.
  auto read = [&](const std::string& name, double fallback) {
    return file.has_attribute("/", name) ? file.read_double_attribute("/", name) : fallback;
  };
  for (const SummaryField& f : summary_fields)
    summary.*f.value = read(std::string("summary_") + f.name, summary.*f.value);
  summary.newton_iterations = static_cast<int>(file.read_double_attribute("/", "summary_newton_iterations"));
  summary.reduced_steps = static_cast<int>(read("summary_reduced_steps", 0));
  return summary;
}

void write_terms(const h5::File& file, const std::vector<std::pair<std::string, time::TermState>>& terms) {
  file.create_group("/terms");
  for (size_t k = 0; k < terms.size(); ++k) {
    const std::string group = "/terms/" + std::to_string(k);
    file.create_group(group);
    file.write_attribute(group, "name", terms[k].first);
    file.create_group(group + "/reals");
    file.create_group(group + "/integers");
    for (const auto& [name, values] : terms[k].second.reals)
      write_reals(file, group + "/reals/" + name, values.data(), values.size());
    for (const auto& [name, values] : terms[k].second.integers)
      write_integers(file, group + "/integers/" + name, values);
  }
}

std::vector<std::pair<std::string, time::TermState>> read_terms(const h5::File& file) {
  std::vector<std::pair<std::string, time::TermState>> terms(file.children("/terms").size());
  for (size_t k = 0; k < terms.size(); ++k) {
    const std::string group = "/terms/" + std::to_string(k);
    terms[k].first = file.read_string_attribute(group, "name").at(0);
    for (const std::string& name : file.children(group + "/reals"))
      terms[k].second.reals[name] = file.read_doubles(group + "/reals/" + name);
    for (const std::string& name : file.children(group + "/integers"))
      terms[k].second.integers[name] = read_integers(file, group + "/integers/" + name);
  }
  return terms;
}

void write_series(const h5::File& file, const std::vector<model::StepRow>& rows) {
  const hsize_t width = rows.empty() ? 0 : rows.front().values.size();
  std::vector<std::int64_t> steps;
  std::vector<double> times, values;
  for (const model::StepRow& row : rows) {
    if (row.values.size() != width) throw std::invalid_argument("checkpoint: series rows of different sizes");
    steps.push_back(row.step);
    times.push_back(row.time);
    values.insert(values.end(), row.values.begin(), row.values.end());
  }
  file.create_group("/series");
  write_integers(file, "/series/step", steps);
  write_reals(file, "/series/time", times.data(), times.size());
  write_reals(file, "/series/values", values.data(), rows.size(), width);
}

std::vector<model::StepRow> read_series(const h5::File& file) {
  const std::vector<std::int64_t> steps = read_integers(file, "/series/step");
  const std::vector<double> times = file.read_doubles("/series/time");
  const std::vector<double> values = file.read_doubles("/series/values");
  const h5::Dims shape = file.shape("/series/values");
  const size_t width = shape.size() == 2 ? shape[1] : 0;
  if (times.size() != steps.size() || values.size() != steps.size() * width)
    throw std::runtime_error("checkpoint " + file.path().string() +
                             ": /series datasets of different lengths");
  std::vector<model::StepRow> rows(steps.size());
  for (size_t r = 0; r < rows.size(); ++r) {
    rows[r].step = static_cast<int>(steps[r]);
    rows[r].time = times[r];
    rows[r].values.assign(values.begin() + r * width, values.begin() + (r + 1) * width);
  }
  return rows;
}

void write_controller(const h5::File& file, const StepControllerState& controller) {
  file.create_group("/controller");
  file.write_attribute("/controller", "next_step", controller.next_step);
  file.write_attribute("/controller", "previous_step", controller.previous_step);
  file.write_attribute("/controller", "has_history", controller.has_history ? 1 : 0);
}

StepControllerState read_controller(const h5::File& file) {
  StepControllerState controller;
  controller.next_step = file.read_double_attribute("/controller", "next_step");
  controller.previous_step = file.read_double_attribute("/controller", "previous_step");
  controller.has_history = file.read_double_attribute("/controller", "has_history") != 0;
  return controller;
}

}  // namespace

bool CheckpointStore::exists() const {
  std::error_code ignored;
  return fs::is_regular_file(state_file(), ignored);
}

fs::path CheckpointStore::frame_file(int k) const {
  return directory_ / ("frame_" + std::to_string(k) + ".h5");
}

void CheckpointStore::write_frame(int k, const model::Frame& frame) {
  h5::silence_errors();
  fs::create_directories(directory_);
  const fs::path path = frame_file(k);
  h5::File file = h5::File::create(path);
  file.write_attribute("/", "time", frame.time);
  write_reals(file, "/position", frame.position.data(), frame.position.size());
  write_reals(file, "/velocity", frame.velocity.data(), frame.velocity.size());
  if (frame.contact_pressure.size() > 0)
    write_reals(file, "/contact_pressure", frame.contact_pressure.data(), frame.contact_pressure.size());
  file.close();
  unsynced_.push_back(path);
}

bool CheckpointStore::has_frame(int k) const {
  std::error_code ignored;
  return fs::is_regular_file(frame_file(k), ignored);
}

model::Frame CheckpointStore::read_frame(int k) const {
  h5::silence_errors();
  const h5::File file = h5::File::open(frame_file(k));
  model::Frame frame;
  frame.time = file.read_double_attribute("/", "time");
  frame.position = read_vector(file, "/position");
  frame.velocity = read_vector(file, "/velocity");
  if (file.exists("/contact_pressure")) frame.contact_pressure = read_vector(file, "/contact_pressure");
  return frame;
}

void CheckpointStore::write(const Checkpoint& c) {
  h5::silence_errors();
  fs::create_directories(directory_);
  const fs::path temporary = state_file().string() + ".tmp";
  {
    h5::File file = h5::File::create(temporary);
    file.write_attribute("/", "format", std::string(checkpoint_format));
    file.write_dataset("/scene", H5T_STD_U8LE, H5T_NATIVE_UCHAR, {c.scene.size()}, c.scene.data());
    file.write_attribute("/", "step", c.state.step);
    file.write_attribute("/", "time", c.state.t);
    file.write_attribute("/", "step_size", c.step_size);
    write_summary(file, c.summary);
    file.create_group("/state");
    write_reals(file, "/state/x", c.state.x.data(), c.state.x.size());
    write_reals(file, "/state/v", c.state.v.data(), c.state.v.size());
    write_reals(file, "/state/a", c.state.a.data(), c.state.a.size());
    file.write_attribute("/state", "last_step", c.state.last_step);  // the predictor's h_{n−1} (midpoint.hpp)
    write_terms(file, c.terms);
    write_series(file, c.rows);
    file.create_group("/frames");
    write_integers(file, "/frames/step",
                   std::vector<std::int64_t>(c.frame_steps.begin(), c.frame_steps.end()));
    if (c.controller) write_controller(file, *c.controller);
    file.close();
  }
  for (const fs::path& frame : unsynced_) sync_to_disk(frame);
  rename_durably(temporary, state_file());
  unsynced_.clear();
}

Checkpoint CheckpointStore::read() const {
  h5::silence_errors();
  const h5::File file = h5::File::open(state_file());
  const std::vector<std::string> format = file.read_string_attribute("/", "format");
  if (format.size() != 1 || format[0] != checkpoint_format)
    throw std::runtime_error("checkpoint " + state_file().string() + ": format is not " + checkpoint_format);
  Checkpoint c;
  for (double byte : file.read_doubles("/scene"))
    c.scene.push_back(static_cast<char>(static_cast<unsigned char>(byte)));
  c.state.step = static_cast<int>(file.read_double_attribute("/", "step"));
  c.state.t = file.read_double_attribute("/", "time");
  c.step_size = file.read_double_attribute("/", "step_size");
  c.summary = read_summary(file);
  c.state.x = read_vector(file, "/state/x");
  c.state.v = read_vector(file, "/state/v");
  c.state.a = read_vector(file, "/state/a");
  // A checkpoint written before last_step existed: 0, the next step's h stands in (scheme.hpp).
  c.state.last_step =
      file.has_attribute("/state", "last_step") ? file.read_double_attribute("/state", "last_step") : 0;
  c.terms = read_terms(file);
  c.rows = read_series(file);
  for (std::int64_t step : read_integers(file, "/frames/step"))
    c.frame_steps.push_back(static_cast<int>(step));
  if (file.exists("/controller")) c.controller = read_controller(file);
  return c;
}

void CheckpointStore::remove() const {
  std::error_code ignored;
  fs::remove_all(directory_, ignored);
}

}  // namespace stoss::run
