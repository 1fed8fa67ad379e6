#include "core/output/result_writer.hpp"

#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <system_error>

#include "core/output/durable_file.hpp"
#include "core/output/h5.hpp"
#include "core/output/layout.hpp"
#include "core/output/xdmf.hpp"

namespace stoss::output {

namespace fs = std::filesystem;

namespace {

#ifdef STOSS_VERSION
constexpr const char* stoss_version = STOSS_VERSION;
#else
constexpr const char* stoss_version = "dev";
#endif

constexpr hsize_t series_chunk_rows = 512;
constexpr hsize_t frame_time_chunk_rows = 64;

void remove_earlier_results(const fs::path& directory) {
  for (const char* name : {result_file_name, incomplete_file_name, xdmf_file_name, xdmf_mesh_file_name})
    fs::remove(directory / name);
}

/// A body or surface name as an HDF5 link name ('/' and a leading '.' are not allowed there).
std::string link_name(std::string name) {
  for (char& c : name)
    if (c == '/') c = '_';
  if (name.empty() || name[0] == '.') name = "_" + name;
  return name;
}

std::vector<std::string> body_names(const mesh::Mesh& mesh) {
  std::vector<std::string> names;
  for (const auto& body : mesh.bodies) names.push_back(body.name);
  return names;
}

void write_root_attributes(const h5::File& file, const model::Model& model) {
  file.write_attribute("/", "format", std::string(result_format));
  file.write_attribute("/", "stoss_version", std::string(stoss_version));
  file.write_attribute("/", "scheme", model::to_string(model.time.scheme));
  file.write_attribute("/", "step", model.time.step);
  file.write_attribute("/", "end", model.time.end);
  file.write_attribute("/", "effects", model.effects);
  if (!model.boundary.empty()) {  // the second axis of series/reaction_force (docs/results.md)
    std::vector<std::string> entries;
    for (const model::Boundary& b : model.boundary) entries.push_back(b.surface);
    file.write_attribute("/", "boundary_entries", entries);
  }
  if (!model.contact.empty()) {  // the second axis of series/contact_force and contact_area
    std::vector<std::string> pairs;
    for (const model::ContactPair& p : model.contact) pairs.push_back(p.slave + " on " + p.master);
    file.write_attribute("/", "contact_pairs", pairs);
  }
  file.write_attribute("/", "scene", model.scene.dump());
  file.write_attribute("/", "complete", 0);
}

void write_mesh(const h5::File& file, const mesh::Mesh& mesh) {
  const hsize_t N = mesh.nodes.size(), E = mesh.hex8.size();
  std::vector<double> nodes;
  for (const auto& x : mesh.nodes) nodes.insert(nodes.end(), x.data(), x.data() + 3);
  std::vector<std::int64_t> hex8;
  for (const auto& h : mesh.hex8) hex8.insert(hex8.end(), h.begin(), h.end());
  const std::vector<std::int32_t> body(mesh.element_body.begin(), mesh.element_body.end());
  file.create_group("/mesh");
  file.write_dataset("/mesh/nodes", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {N, 3}, nodes.data());
  file.write_dataset("/mesh/hex8", H5T_STD_I64LE, H5T_NATIVE_INT64, {E, 8}, hex8.data());
  file.write_dataset("/mesh/body", H5T_STD_I32LE, H5T_NATIVE_INT32, {E}, body.data());
  file.write_attribute("/mesh/body", "names", body_names(mesh));
  std::vector<std::int32_t> node_body(N, -1);
  for (size_t b = 0; b < mesh.bodies.size(); ++b)
    for (int n = mesh.bodies[b].node_begin; n < mesh.bodies[b].node_end; ++n)
      node_body[n] = static_cast<std::int32_t>(b);
  file.write_dataset("/mesh/node_body", H5T_STD_I32LE, H5T_NATIVE_INT32, {N}, node_body.data());
  file.create_group("/mesh/surfaces", true);
  for (const auto& body : mesh.bodies) {
    const std::string group = "/mesh/surfaces/" + link_name(body.name);
    file.create_group(group, true);
    for (const auto& [name, quads] : body.surfaces) {
      std::vector<std::int64_t> rows;
      for (const auto& q : quads) rows.insert(rows.end(), q.begin(), q.end());
      const std::string dataset = group + "/" + link_name(name);
      file.write_dataset(dataset, H5T_STD_I64LE, H5T_NATIVE_INT64, {quads.size(), 4}, rows.data());
      file.write_attribute(dataset, "name", body.name + "/" + name);
    }
  }
}

h5::Dims row_shape(const model::SeriesSpec& spec) {
  h5::Dims dims;
  for (int n : spec.row_shape()) dims.push_back(static_cast<hsize_t>(n));
  return dims;
}

void create_series(const h5::File& file, const model::SeriesLayout& layout) {
  file.create_group("/series", true);
  file.create_extendible("/series/time", H5T_IEEE_F64LE, {}, series_chunk_rows);
  for (const auto& spec : layout.series)
    file.create_extendible("/series/" + spec.name, spec.integer ? H5T_STD_I32LE : H5T_IEEE_F64LE,
                           row_shape(spec), series_chunk_rows);
}

void create_frames(const h5::File& file) {
  file.create_group("/frames", true);
  file.create_extendible("/frames/time", H5T_IEEE_F64LE, {}, frame_time_chunk_rows);
}

/// Columns [offset, offset + components) of `rows` buffered rows of `width` values, row-major.
template <typename T>
std::vector<T> column_block(const std::vector<double>& values, int width, int offset, int components) {
  const size_t rows = values.size() / width;
  std::vector<T> out;
  out.reserve(rows * components);
  for (size_t r = 0; r < rows; ++r)
    for (int c = 0; c < components; ++c) {
      const double v = values[r * width + offset + c];
      if constexpr (std::is_integral_v<T>)
        out.push_back(static_cast<T>(std::llround(v)));
      else
        out.push_back(v);
    }
  return out;
}

void check_size(const Eigen::VectorXd& field, long expected, const char* name) {
  if (field.size() != expected)
    throw std::invalid_argument(std::string("frame field ") + name + " has " + std::to_string(field.size()) +
                                " values, expected " + std::to_string(expected));
}

}  // namespace

/// The state of a run between begin() and end().
struct ResultWriter::Run {
  h5::File file;
  model::SeriesLayout layout;
  long node_count = 0;
  long element_count = 0;
  std::vector<double> buffered_times;
  std::vector<double> buffered_values;  ///< rows of layout.row_size() values
  std::vector<double> frame_times;
  std::optional<bool> contact_pressure;  ///< decided by the first frame
  std::optional<bool> stress;            ///< cauchy_stress and von_mises, decided by the first frame
  Eigen::VectorXd reference;             ///< X, 3 per node

  void flush_rows();
  void append_series(const model::SeriesSpec& spec, int offset);
  void check_frame(const model::Frame& frame);
  XdmfLayout xdmf_layout() const;
};

void ResultWriter::Run::flush_rows() {
  if (buffered_times.empty()) return;
  file.append_rows("/series/time", H5T_NATIVE_DOUBLE, buffered_times.size(), buffered_times.data());
  int offset = 0;
  for (const auto& spec : layout.series) {
    append_series(spec, offset);
    offset += spec.components;
  }
  buffered_times.clear();
  buffered_values.clear();
}

void ResultWriter::Run::append_series(const model::SeriesSpec& spec, int offset) {
  const std::string name = "/series/" + spec.name;
  const int width = layout.row_size();
  const hsize_t rows = buffered_times.size();
  if (spec.integer) {
    const auto block = column_block<std::int32_t>(buffered_values, width, offset, spec.components);
    file.append_rows(name, H5T_NATIVE_INT32, rows, block.data());
  } else {
    const auto block = column_block<double>(buffered_values, width, offset, spec.components);
    file.append_rows(name, H5T_NATIVE_DOUBLE, rows, block.data());
  }
}

namespace {

/// Whether the optional `field` is in the frame; the first frame decides for every later one.
bool decide(std::optional<bool>& decided, const Eigen::VectorXd& field, const char* name) {
  const bool present = field.size() > 0;
  if (!decided) decided = present;
  if (present != *decided)
    throw std::invalid_argument(std::string(*decided ? "frame without " : "frame with ") + name +
                                (*decided ? " after frames with it" : " after frames without it"));
  return present;
}

}  // namespace

void ResultWriter::Run::check_frame(const model::Frame& frame) {
  check_size(frame.position, 3 * node_count, "position");
  check_size(frame.velocity, 3 * node_count, "velocity");
  if (decide(contact_pressure, frame.contact_pressure, "contact_pressure"))
    check_size(frame.contact_pressure, node_count, "contact_pressure");
  if (decide(stress, frame.cauchy_stress, "cauchy_stress")) {
    check_size(frame.cauchy_stress, 6 * element_count, "cauchy_stress");
    check_size(frame.von_mises, element_count, "von_mises");
  }
}

XdmfLayout ResultWriter::Run::xdmf_layout() const {
  return XdmfLayout{
      result_file_name,      node_count, element_count, frame_times, contact_pressure.value_or(false),
      stress.value_or(false)};
}

ResultWriter::ResultWriter(std::filesystem::path directory) : directory_(std::move(directory)) {}

ResultWriter::~ResultWriter() = default;

void ResultWriter::begin(const model::Model& model, const model::SeriesLayout& layout) {
  h5::silence_errors();
  run_.reset();
  fs::create_directories(directory_);
  remove_earlier_results(directory_);
  auto run = std::make_unique<Run>();
  run->file = h5::File::create(directory_ / partial_file_name);
  run->layout = layout;
  run->node_count = model.mesh.node_count();
  run->element_count = model.mesh.element_count();
  write_root_attributes(run->file, model);
  write_mesh(run->file, model.mesh);
  create_series(run->file, layout);
  create_frames(run->file);
  run->reference = model.mesh.reference_positions();
  run_ = std::move(run);
}

void ResultWriter::step(const model::StepRow& row) {
  if (!run_) throw std::logic_error("ResultWriter::step called outside begin()..end()");
  const int width = run_->layout.row_size();
  if (static_cast<int>(row.values.size()) != width)
    throw std::invalid_argument("step row has " + std::to_string(row.values.size()) + " values, the layout " +
                                std::to_string(width));
  run_->buffered_times.push_back(row.time);
  run_->buffered_values.insert(run_->buffered_values.end(), row.values.begin(), row.values.end());
  if (static_cast<int>(run_->buffered_times.size()) >= rows_per_flush) {
    h5::silence_errors();
    run_->flush_rows();
  }
}

void ResultWriter::frame(const model::Frame& frame) {
  if (!run_) throw std::logic_error("ResultWriter::frame called outside begin()..end()");
  h5::silence_errors();
  run_->check_frame(frame);
  const h5::File& file = run_->file;
  const long k = static_cast<long>(run_->frame_times.size());
  const hsize_t N = run_->node_count, E = run_->element_count;
  const auto write = [&](const char* name, const h5::Dims& dims, const double* data) {
    file.write_dataset(frame_dataset(k, name), H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dims, data);
  };
  file.create_group("/frames/" + std::to_string(k));
  file.write_attribute("/frames/" + std::to_string(k), "time", frame.time);
  write("position", {N, 3}, frame.position.data());
  write("velocity", {N, 3}, frame.velocity.data());
  const Eigen::VectorXd displacement = frame.position - run_->reference;
  write("displacement", {N, 3}, displacement.data());
  if (*run_->contact_pressure) write("contact_pressure", {N}, frame.contact_pressure.data());
  if (*run_->stress) {
    write("cauchy_stress", {E, 6}, frame.cauchy_stress.data());
    write("von_mises", {E}, frame.von_mises.data());
  }
  file.append_rows("/frames/time", H5T_NATIVE_DOUBLE, 1, &frame.time);
  run_->frame_times.push_back(frame.time);
}

void ResultWriter::end(const model::Summary& summary) {
  if (!run_) return;
  h5::silence_errors();
  const std::unique_ptr<Run> run = std::move(run_);
  run->flush_rows();
  run->file.write_attribute("/", "wall_seconds", summary.wall_seconds);
  run->file.write_attribute("/", "complete", summary.completed ? 1 : 0);
  run->file.write_attribute("/", "verdict", summary.verdict);  // docs/results.md, "Verdict"
  run->file.write_attribute("/", "checks", model::checks_json(summary.checks).dump());
  run->file.close();
  if (summary.completed) {
    write_durably(directory_ / xdmf_file_name, xdmf_document(run->xdmf_layout()));
    write_durably(directory_ / xdmf_mesh_file_name, xdmf_mesh_document(run->xdmf_layout()));
    rename_durably(directory_ / partial_file_name, directory_ / result_file_name);
  } else {
    rename_durably(directory_ / partial_file_name, directory_ / incomplete_file_name);
  }
}

}  // namespace stoss::output
