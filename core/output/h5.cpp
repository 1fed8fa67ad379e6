#include "core/output/h5.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace stoss::output::h5 {

void silence_errors() {
  thread_local bool silenced = false;
  if (silenced) return;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  silenced = true;
}

Id::Id(Id&& other) noexcept : id_(std::exchange(other.id_, H5I_INVALID_HID)), close_(other.close_) {}

Id& Id::operator=(Id&& other) noexcept {
  if (this != &other) {
    reset();
    id_ = std::exchange(other.id_, H5I_INVALID_HID);
    close_ = other.close_;
  }
  return *this;
}

void Id::reset() noexcept {
  close();
}

herr_t Id::close() noexcept {
  herr_t status = 0;
  if (id_ >= 0 && close_) status = close_(id_);
  id_ = H5I_INVALID_HID;
  return status;
}

Id string_type() {
  Id type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  return type;
}

namespace {

herr_t keep_innermost(unsigned n, const H5E_error2_t* error, void* message) {
  if (n == 0 && error->desc) *static_cast<std::string*>(message) = error->desc;
  return 0;
}

std::string innermost_error() {
  std::string message;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_innermost, &message);
  return message;
}

/// Frees the strings HDF5 allocated for a variable-length read.
void reclaim_strings(hid_t type, hid_t space, void* buffer) {
#if H5_VERSION_GE(1, 12, 0)
  H5Treclaim(type, space, H5P_DEFAULT, buffer);
#else
  H5Dvlen_reclaim(type, space, H5P_DEFAULT, buffer);
#endif
}

Id scalar_space() {
  return Id(H5Screate(H5S_SCALAR), H5Sclose);
}

Id simple_space(const Dims& dims, const Dims& max_dims) {
  return Id(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), max_dims.data()), H5Sclose);
}

Dims space_dims(hid_t space) {
  Dims dims(static_cast<size_t>(std::max(0, H5Sget_simple_extent_ndims(space))));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return dims;
}

hsize_t product(const Dims& dims, size_t from = 0) {
  hsize_t n = 1;
  for (size_t i = from; i < dims.size(); ++i) n *= dims[i];
  return n;
}

}  // namespace

File File::create(const std::filesystem::path& path) {
  silence_errors();
  Id access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_fclose_degree(access.get(), H5F_CLOSE_STRONG);
  File file(path, Id(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get()), H5Fclose));
  if (!file.is_open()) file.fail("create file", "");
  return file;
}

File File::open(const std::filesystem::path& path) {
  silence_errors();
  Id access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_fclose_degree(access.get(), H5F_CLOSE_STRONG);
  File file(path, Id(H5Fopen(path.c_str(), H5F_ACC_RDONLY, access.get()), H5Fclose));
  if (!file.is_open()) file.fail("open file", "");
  return file;
}

void File::close() {
  check(id_.close(), "close file", "");
}

void File::fail(const std::string& what, const std::string& object) const {
  std::string message =
      "HDF5: cannot " + what + (object.empty() ? " " : " '" + object + "' in ") + path_.string();
  const std::string detail = innermost_error();
  if (!detail.empty()) message += ": " + detail;
  throw std::runtime_error(message);
}

hid_t File::check_id(hid_t id, const std::string& what, const std::string& object) const {
  if (id < 0) fail(what, object);
  return id;
}

void File::check(herr_t status, const std::string& what, const std::string& object) const {
  if (status < 0) fail(what, object);
}

void File::create_group(const std::string& name, bool track_order) const {
  Id properties(H5Pcreate(H5P_GROUP_CREATE), H5Pclose);
  if (track_order)
    H5Pset_link_creation_order(properties.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED);
  Id group(check_id(H5Gcreate2(id_.get(), name.c_str(), H5P_DEFAULT, properties.get(), H5P_DEFAULT),
                    "create group", name),
           H5Gclose);
}

bool File::exists(const std::string& path) const {
  for (size_t slash = path.find('/', 1);; slash = path.find('/', slash + 1)) {
    const std::string prefix = path.substr(0, slash);
    if (prefix.empty() || prefix == "/") return true;
    if (H5Lexists(id_.get(), prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (slash == std::string::npos) return true;
  }
}

std::vector<std::string> File::children(const std::string& group) const {
  Id g(check_id(H5Gopen2(id_.get(), group.c_str(), H5P_DEFAULT), "open group", group), H5Gclose);
  H5G_info_t info;
  check(H5Gget_info(g.get(), &info), "inspect group", group);
  const bool by_creation =
      H5Lget_name_by_idx(g.get(), ".", H5_INDEX_CRT_ORDER, H5_ITER_INC, 0, nullptr, 0, H5P_DEFAULT) >= 0 ||
      info.nlinks == 0;
  const H5_index_t index = by_creation ? H5_INDEX_CRT_ORDER : H5_INDEX_NAME;
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t size = H5Lget_name_by_idx(g.get(), ".", index, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (size < 0) fail("list links of", group);
    std::string name(static_cast<size_t>(size), '\0');
    H5Lget_name_by_idx(g.get(), ".", index, H5_ITER_INC, i, name.data(), name.size() + 1, H5P_DEFAULT);
    names.push_back(std::move(name));
  }
  return names;
}

void File::replace_attribute(const std::string& object, const std::string& name, hid_t file_type, hid_t space,
                             hid_t memory_type, const void* data) const {
  const std::string where = object + "@" + name;
  if (has_attribute(object, name))
    check(H5Adelete_by_name(id_.get(), object.c_str(), name.c_str(), H5P_DEFAULT), "replace attribute",
          where);
  Id attribute(check_id(H5Acreate_by_name(id_.get(), object.c_str(), name.c_str(), file_type, space,
                                          H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                        "create attribute", where),
               H5Aclose);
  check(H5Awrite(attribute.get(), memory_type, data), "write attribute", where);
}

void File::write_attribute(const std::string& object, const std::string& name, double value) const {
  replace_attribute(object, name, H5T_IEEE_F64LE, scalar_space().get(), H5T_NATIVE_DOUBLE, &value);
}

void File::write_attribute(const std::string& object, const std::string& name, int value) const {
  replace_attribute(object, name, H5T_STD_I32LE, scalar_space().get(), H5T_NATIVE_INT, &value);
}

void File::write_attribute(const std::string& object, const std::string& name,
                           const std::string& value) const {
  const Id type = string_type();
  const char* text = value.c_str();
  replace_attribute(object, name, type.get(), scalar_space().get(), type.get(), &text);
}

void File::write_attribute(const std::string& object, const std::string& name,
                           const std::vector<std::string>& values) const {
  const Id type = string_type();
  std::vector<const char*> texts;
  for (const auto& v : values) texts.push_back(v.c_str());
  const Dims dims{values.size()};
  replace_attribute(object, name, type.get(), simple_space(dims, dims).get(), type.get(), texts.data());
}

bool File::has_attribute(const std::string& object, const std::string& name) const {
  return H5Aexists_by_name(id_.get(), object.c_str(), name.c_str(), H5P_DEFAULT) > 0;
}

Id File::open_attribute(const std::string& object, const std::string& name) const {
  return Id(check_id(H5Aopen_by_name(id_.get(), object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
                     "open attribute", object + "@" + name),
            H5Aclose);
}

std::vector<std::string> File::read_string_attribute(const std::string& object,
                                                     const std::string& name) const {
  const std::string where = object + "@" + name;
  const Id attribute = open_attribute(object, name);
  const Id stored(check_id(H5Aget_type(attribute.get()), "inspect attribute", where), H5Tclose);
  if (H5Tget_class(stored.get()) != H5T_STRING) fail("read as string the attribute", where);
  const Id space(H5Aget_space(attribute.get()), H5Sclose);
  const auto count = static_cast<size_t>(H5Sget_simple_extent_npoints(space.get()));
  std::vector<std::string> out;
  if (H5Tis_variable_str(stored.get()) > 0) {
    const Id type = string_type();
    std::vector<char*> texts(count, nullptr);
    check(H5Aread(attribute.get(), type.get(), texts.data()), "read attribute", where);
    for (char* t : texts) out.emplace_back(t ? t : "");
    reclaim_strings(type.get(), space.get(), texts.data());
  } else {
    const size_t size = H5Tget_size(stored.get());
    std::string buffer(count * size, '\0');
    check(H5Aread(attribute.get(), stored.get(), buffer.data()), "read attribute", where);
    for (size_t i = 0; i < count; ++i) {
      const std::string element = buffer.substr(i * size, size);
      out.push_back(element.substr(0, element.find('\0')));
    }
  }
  return out;
}

double File::read_double_attribute(const std::string& object, const std::string& name) const {
  const Id attribute = open_attribute(object, name);
  double value = 0;
  check(H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value), "read as number the attribute",
        object + "@" + name);
  return value;
}

void File::write_dataset(const std::string& name, hid_t file_type, hid_t memory_type, const Dims& dims,
                         const void* data) const {
  const Id space = simple_space(dims, dims);
  Id dataset(check_id(H5Dcreate2(id_.get(), name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                                 H5P_DEFAULT),
                      "create dataset", name),
             H5Dclose);
  if (product(dims) > 0)
    check(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write dataset", name);
}

void File::create_extendible(const std::string& name, hid_t file_type, const Dims& row_shape,
                             hsize_t chunk_rows) const {
  Dims dims{0}, max_dims{H5S_UNLIMITED}, chunk{chunk_rows};
  for (hsize_t n : row_shape) {
    dims.push_back(n);
    max_dims.push_back(n);
    chunk.push_back(std::max<hsize_t>(n, 1));
  }
  Id properties(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  check(H5Pset_chunk(properties.get(), static_cast<int>(chunk.size()), chunk.data()), "chunk dataset", name);
  const Id space = simple_space(dims, max_dims);
  Id dataset(check_id(H5Dcreate2(id_.get(), name.c_str(), file_type, space.get(), H5P_DEFAULT,
                                 properties.get(), H5P_DEFAULT),
                      "create dataset", name),
             H5Dclose);
}

Id File::open_dataset(const std::string& name) const {
  return Id(check_id(H5Dopen2(id_.get(), name.c_str(), H5P_DEFAULT), "open dataset", name), H5Dclose);
}

void File::append_rows(const std::string& name, hid_t memory_type, hsize_t rows, const void* data) const {
  const Id dataset = open_dataset(name);
  Dims dims = space_dims(Id(H5Dget_space(dataset.get()), H5Sclose).get());
  Dims start(dims.size(), 0), count = dims;
  start[0] = dims[0];
  count[0] = rows;
  dims[0] += rows;
  check(H5Dset_extent(dataset.get(), dims.data()), "extend dataset", name);
  const Id file_space(H5Dget_space(dataset.get()), H5Sclose);
  check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
        "select rows of dataset", name);
  const Id memory_space = simple_space(count, count);
  check(H5Dwrite(dataset.get(), memory_type, memory_space.get(), file_space.get(), H5P_DEFAULT, data),
        "append to dataset", name);
}

Dims File::shape(const std::string& name) const {
  const Id dataset = open_dataset(name);
  return space_dims(Id(H5Dget_space(dataset.get()), H5Sclose).get());
}

bool File::is_integer(const std::string& name) const {
  const Id dataset = open_dataset(name);
  const Id type(H5Dget_type(dataset.get()), H5Tclose);
  return H5Tget_class(type.get()) == H5T_INTEGER;
}

std::vector<double> File::read_doubles(const std::string& name) const {
  const Dims dims = shape(name);
  return dims.empty() ? read_rows(name, 0, 1) : read_rows(name, 0, dims[0]);
}

std::vector<double> File::read_rows(const std::string& name, hsize_t first, hsize_t count) const {
  const Id dataset = open_dataset(name);
  const Id file_space(H5Dget_space(dataset.get()), H5Sclose);
  Dims dims = space_dims(file_space.get());
  if (dims.empty()) dims = {1};
  if (first + count > dims[0])
    throw std::out_of_range("rows [" + std::to_string(first) + ", " + std::to_string(first + count) +
                            ") are outside dataset '" + name + "' of " + std::to_string(dims[0]) +
                            " rows in " + path_.string());
  std::vector<double> out(count * product(dims, 1));
  if (out.empty()) return out;
  Dims start(dims.size(), 0), extent = dims;
  start[0] = first;
  extent[0] = count;
  if (H5Sget_simple_extent_ndims(file_space.get()) > 0)
    check(
        H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, extent.data(), nullptr),
        "select rows of dataset", name);
  const Id memory_space = simple_space(extent, extent);
  check(H5Dread(dataset.get(), H5T_NATIVE_DOUBLE, memory_space.get(), file_space.get(), H5P_DEFAULT,
                out.data()),
        "read dataset", name);
  return out;
}

}  // namespace stoss::output::h5
