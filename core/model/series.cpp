#include "core/model/series.hpp"

#include <cmath>
#include <cstdint>

namespace stoss::model {

std::vector<int> SeriesSpec::row_shape() const {
  if (items == 0) return components == 1 ? std::vector<int>{} : std::vector<int>{components};
  const int width = components / items;
  return width == 1 ? std::vector<int>{items} : std::vector<int>{items, width};
}

SeriesSpec SeriesSpec::of_shape(std::string name, const std::vector<int>& shape, bool integer) {
  SeriesSpec spec{std::move(name), 1, integer, 0};
  for (int n : shape) spec.components *= n;
  if (shape.size() == 2) spec.items = shape[0];
  return spec;
}

std::vector<std::string> csv_columns(const SeriesSpec& spec) {
  const std::vector<int> shape = spec.row_shape();
  if (shape.empty()) return {spec.name};
  static const char* const xyz[3] = {"_x", "_y", "_z"};
  std::vector<std::string> out;
  if (shape.size() == 1) {
    for (int c = 0; c < shape[0]; ++c)
      out.push_back(spec.name + (shape[0] == 3 && spec.items == 0 ? xyz[c] : "_" + std::to_string(c)));
    return out;
  }
  for (int i = 0; i < shape[0]; ++i)
    for (int c = 0; c < shape[1]; ++c)
      out.push_back(spec.name + "_" + std::to_string(i) + (shape[1] == 3 ? xyz[c] : "_" + std::to_string(c)));
  return out;
}

namespace {

nlohmann::json number_json(double value, bool integer) {
  if (!std::isfinite(value)) return nullptr;
  if (integer) return static_cast<std::int64_t>(std::llround(value));
  return value;
}

nlohmann::json numbers_json(const double* values, int count, bool integer) {
  nlohmann::json out = nlohmann::json::array();
  for (int c = 0; c < count; ++c) out.push_back(number_json(values[c], integer));
  return out;
}

}  // namespace

nlohmann::json row_json(const SeriesSpec& spec, const double* values) {
  const std::vector<int> shape = spec.row_shape();
  if (shape.empty()) return number_json(values[0], spec.integer);
  if (shape.size() == 1) return numbers_json(values, shape[0], spec.integer);
  nlohmann::json out = nlohmann::json::array();
  for (int i = 0; i < shape[0]; ++i)
    out.push_back(numbers_json(values + i * shape[1], shape[1], spec.integer));
  return out;
}

int SeriesLayout::index_of(const std::string& name) const {
  int offset = 0;
  for (const auto& s : series) {
    if (s.name == name) return offset;
    offset += s.components;
  }
  return -1;
}

int SeriesLayout::row_size() const {
  int n = 0;
  for (const auto& s : series) n += s.components;
  return n;
}

}  // namespace stoss::model
