#include "core/output/result_reader.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/output/h5.hpp"
#include "core/output/layout.hpp"
#include "core/output/number_text.hpp"

namespace stoss::output {

namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

Eigen::MatrixXd as_matrix(const std::vector<double>& values, Eigen::Index rows, Eigen::Index cols) {
  return Eigen::Map<const RowMajor>(values.data(), rows, cols);
}

Eigen::Index row_width(const h5::Dims& dims) {
  Eigen::Index width = 1;
  for (size_t i = 1; i < dims.size(); ++i) width *= static_cast<Eigen::Index>(dims[i]);
  return width;
}

}  // namespace

ResultFile::ResultFile(std::unique_ptr<h5::File> file) : file_(std::move(file)) {}
ResultFile::ResultFile(ResultFile&&) noexcept = default;
ResultFile& ResultFile::operator=(ResultFile&&) noexcept = default;
ResultFile::~ResultFile() = default;

ResultFile ResultFile::open(const std::filesystem::path& path) {
  return ResultFile(std::make_unique<h5::File>(h5::File::open(path)));
}

const std::filesystem::path& ResultFile::path() const {
  return file_->path();
}

std::vector<std::string> ResultFile::series_names() const {
  h5::silence_errors();
  return file_->children("/series");
}

std::string ResultFile::series_dataset(const std::string& name) const {
  h5::silence_errors();
  const std::string dataset = "/series/" + name;
  if (!file_->exists(dataset)) throw std::out_of_range("no series '" + name + "' in " + path().string());
  return dataset;
}

Eigen::MatrixXd ResultFile::series(const std::string& name) const {
  const std::string dataset = series_dataset(name);
  const h5::Dims dims = file_->shape(dataset);
  const Eigen::Index rows = dims.empty() ? 1 : static_cast<Eigen::Index>(dims[0]);
  return as_matrix(file_->read_doubles(dataset), rows, row_width(dims));
}

bool ResultFile::series_is_integer(const std::string& name) const {
  return file_->is_integer(series_dataset(name));
}

model::SeriesSpec ResultFile::series_spec(const std::string& name) const {
  const h5::Dims dims = file_->shape(series_dataset(name));
  std::vector<int> shape;
  for (size_t i = 1; i < dims.size(); ++i) shape.push_back(static_cast<int>(dims[i]));
  return model::SeriesSpec::of_shape(name, shape, series_is_integer(name));
}

bool ResultFile::has_attribute(const std::string& name) const {
  h5::silence_errors();
  return file_->has_attribute("/", name);
}

std::vector<std::string> ResultFile::attribute_strings(const std::string& name) const {
  if (!has_attribute(name)) throw std::out_of_range("no attribute '" + name + "' in " + path().string());
  return file_->read_string_attribute("/", name);
}

std::string ResultFile::attribute_string(const std::string& name) const {
  const auto values = attribute_strings(name);
  if (values.size() != 1)
    throw std::runtime_error("attribute '" + name + "' in " + path().string() + " holds " +
                             std::to_string(values.size()) + " strings, not one");
  return values.front();
}

double ResultFile::attribute_double(const std::string& name) const {
  if (!has_attribute(name)) throw std::out_of_range("no attribute '" + name + "' in " + path().string());
  return file_->read_double_attribute("/", name);
}

Eigen::MatrixXd ResultFile::mesh_nodes() const {
  h5::silence_errors();
  const auto values = file_->read_doubles("/mesh/nodes");
  return as_matrix(values, static_cast<Eigen::Index>(values.size() / 3), 3);
}

Eigen::Matrix<std::int64_t, Eigen::Dynamic, 8> ResultFile::mesh_hex8() const {
  h5::silence_errors();
  const auto values = file_->read_doubles("/mesh/hex8");
  return as_matrix(values, static_cast<Eigen::Index>(values.size() / 8), 8).cast<std::int64_t>();
}

std::vector<std::string> ResultFile::body_names() const {
  h5::silence_errors();
  return file_->read_string_attribute("/mesh/body", "names");
}

Eigen::VectorXi ResultFile::element_bodies() const {
  h5::silence_errors();
  const auto values = file_->read_doubles("/mesh/body");
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()))
      .cast<int>();
}

Eigen::VectorXi ResultFile::node_bodies() const {
  h5::silence_errors();
  const auto values = file_->read_doubles("/mesh/node_body");
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()))
      .cast<int>();
}

std::map<std::string, Eigen::Matrix<std::int64_t, Eigen::Dynamic, 4>> ResultFile::surfaces() const {
  h5::silence_errors();
  std::map<std::string, Eigen::Matrix<std::int64_t, Eigen::Dynamic, 4>> out;
  if (!file_->exists("/mesh/surfaces")) return out;
  for (const auto& body : file_->children("/mesh/surfaces"))
    for (const auto& surface : file_->children("/mesh/surfaces/" + body)) {
      const std::string dataset = "/mesh/surfaces/" + body + "/" + surface;
      const auto values = file_->read_doubles(dataset);
      out[file_->read_string_attribute(dataset, "name").at(0)] =
          as_matrix(values, static_cast<Eigen::Index>(values.size() / 4), 4).cast<std::int64_t>();
    }
  return out;
}

bool ResultFile::format_1() const {
  return has_attribute("format") && attribute_string("format") == result_format_1;
}

int ResultFile::frame_count() const {
  h5::silence_errors();
  return static_cast<int>(file_->shape("/frames/time").at(0));
}

Eigen::VectorXd ResultFile::frame_times() const {
  h5::silence_errors();
  const auto values = file_->read_doubles("/frames/time");
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

Eigen::MatrixXd ResultFile::frame_rows(const std::string& name, int k, int width) const {
  h5::silence_errors();
  if (k < 0) throw std::out_of_range("frame index " + std::to_string(k) + " is negative");
  if (format_1()) {
    const auto values = file_->read_rows("/frames/" + name, static_cast<hsize_t>(k), 1);
    return as_matrix(values, static_cast<Eigen::Index>(values.size() / width), width);
  }
  if (k >= frame_count())
    throw std::out_of_range("frame " + std::to_string(k) + " is outside the " +
                            std::to_string(frame_count()) + " frames of " + path().string());
  const std::string dataset = frame_dataset(k, name);
  if (!file_->exists(dataset)) throw std::out_of_range("no dataset " + dataset + " in " + path().string());
  const auto values = file_->read_doubles(dataset);
  return as_matrix(values, static_cast<Eigen::Index>(values.size() / width), width);
}

Eigen::MatrixXd ResultFile::frame_positions(int k) const {
  return frame_rows("position", k, 3);
}

Eigen::MatrixXd ResultFile::frame_velocities(int k) const {
  return frame_rows("velocity", k, 3);
}

Eigen::MatrixXd ResultFile::frame_displacements(int k) const {
  return frame_rows("displacement", k, 3);
}

bool ResultFile::has_contact_pressure() const {
  h5::silence_errors();
  return format_1() ? file_->exists("/frames/contact_pressure")
                    : frame_count() > 0 && file_->exists(frame_dataset(0, "contact_pressure"));
}

Eigen::VectorXd ResultFile::frame_contact_pressure(int k) const {
  return frame_rows("contact_pressure", k, 1).col(0);
}

bool ResultFile::has_stress() const {
  h5::silence_errors();
  return !format_1() && frame_count() > 0 && file_->exists(frame_dataset(0, "von_mises"));
}

Eigen::MatrixXd ResultFile::frame_cauchy_stress(int k) const {
  return frame_rows("cauchy_stress", k, 6);
}

Eigen::VectorXd ResultFile::frame_von_mises(int k) const {
  return frame_rows("von_mises", k, 1).col(0);
}

namespace {

/// One named, loaded series for the CSV table.
struct Column {
  model::SeriesSpec spec;
  RowMajor values;  ///< S rows of spec.components
};

std::vector<Column> load_columns(const ResultFile& file) {
  std::vector<Column> columns;
  for (const auto& name : file.series_names()) columns.push_back({file.series_spec(name), file.series(name)});
  return columns;
}

void append_cell(std::string& line, const std::string& cell) {
  if (!line.empty()) line += ',';
  line += cell;
}

std::string number_text(double value, bool integer) {
  return integer ? std::to_string(std::llround(value)) : shortest_text(value);
}

}  // namespace

nlohmann::json series_json(const std::filesystem::path& path) {
  nlohmann::json out = nlohmann::json::object();
  for (const Column& column : load_columns(ResultFile::open(path))) {
    nlohmann::json rows = nlohmann::json::array();
    for (Eigen::Index r = 0; r < column.values.rows(); ++r)
      rows.push_back(model::row_json(column.spec, column.values.row(r).data()));
    out[column.spec.name] = std::move(rows);
  }
  return out;
}

std::string series_csv(const std::filesystem::path& path) {
  const auto columns = load_columns(ResultFile::open(path));
  std::string header;
  Eigen::Index rows = columns.empty() ? 0 : columns.front().values.rows();
  for (const auto& column : columns) {
    for (const auto& cell : model::csv_columns(column.spec)) append_cell(header, cell);
    rows = std::min(rows, column.values.rows());
  }
  std::string out = header + '\n';
  for (Eigen::Index r = 0; r < rows; ++r) {
    std::string line;
    for (const auto& column : columns)
      for (Eigen::Index c = 0; c < column.values.cols(); ++c)
        append_cell(line, number_text(column.values(r, c), column.spec.integer));
    out += line + '\n';
  }
  return out;
}

}  // namespace stoss::output
