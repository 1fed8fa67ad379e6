#pragma once
/// @file A thin RAII layer over the HDF5 C API, sized for the result file. Private to core/output.

#include <hdf5.h>

#include <filesystem>
#include <string>
#include <vector>

namespace stoss::output::h5 {

/// Turns off HDF5's automatic error printing on the calling thread.
/// @note With a thread-safe HDF5 the error stack is per thread, so every entry point calls this.
void silence_errors();

/// Owns one HDF5 identifier and closes it with the function that matches its kind.
class Id {
 public:
  using Closer = herr_t (*)(hid_t);

  Id() = default;
  Id(hid_t id, Closer close) : id_(id), close_(close) {}
  Id(Id&& other) noexcept;
  Id& operator=(Id&& other) noexcept;
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  ~Id() { reset(); }

  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  /// Closes now, ignoring failure (destructor and exception paths).
  void reset() noexcept;
  /// Closes now and returns the status of the close call.
  herr_t close() noexcept;

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer close_ = nullptr;
};

/// Shape of a dataset, slowest dimension first.
using Dims = std::vector<hsize_t>;

/// A variable-length UTF-8 string type (used for every string the result file stores).
Id string_type();

/// An open HDF5 file. Every failure throws std::runtime_error naming the file, the object and
/// the innermost message of HDF5's error stack.
class File {
 public:
  File() = default;
  /// Creates (truncating) a file for writing.
  static File create(const std::filesystem::path& path);
  /// Opens an existing file read-only.
  static File open(const std::filesystem::path& path);

  bool is_open() const { return id_.valid(); }
  const std::filesystem::path& path() const { return path_; }
  /// Closes the file, throwing if HDF5 cannot flush it.
  void close();
  /// Closes the file, ignoring failure.
  void abandon() noexcept { id_.reset(); }

  /// Throws "HDF5: cannot <what> '<object>' in <file>: <HDF5's message>"; an empty object names only the
  /// file.
  [[noreturn]] void fail(const std::string& what, const std::string& object) const;
  /// `id`, or fail(what, object) when it is negative.
  hid_t check_id(hid_t id, const std::string& what, const std::string& object) const;
  /// fail(what, object) when `status` is negative.
  void check(herr_t status, const std::string& what, const std::string& object) const;

  /// Creates a group; `track_order` keeps its links in creation order for children().
  void create_group(const std::string& name, bool track_order = false) const;
  /// Whether every link of an absolute path exists ("/series/time").
  bool exists(const std::string& path) const;
  /// Names of a group's links, in creation order where tracked, else by name.
  std::vector<std::string> children(const std::string& group) const;

  /// Attributes of `object` ("/" for the root); writing replaces an existing one.
  void write_attribute(const std::string& object, const std::string& name, double value) const;
  void write_attribute(const std::string& object, const std::string& name, int value) const;
  void write_attribute(const std::string& object, const std::string& name, const std::string& value) const;
  void write_attribute(const std::string& object, const std::string& name,
                       const std::vector<std::string>& values) const;
  bool has_attribute(const std::string& object, const std::string& name) const;
  /// A scalar or array string attribute (fixed or variable length) as its elements.
  std::vector<std::string> read_string_attribute(const std::string& object, const std::string& name) const;
  /// A numeric scalar attribute, converted to double.
  double read_double_attribute(const std::string& object, const std::string& name) const;

  /// Writes a whole fixed-size dataset from `data` (row-major, of `memory_type`).
  void write_dataset(const std::string& name, hid_t file_type, hid_t memory_type, const Dims& dims,
                     const void* data) const;
  /// Creates a chunked dataset of shape [0, row_shape...] that grows along its first dimension.
  void create_extendible(const std::string& name, hid_t file_type, const Dims& row_shape,
                         hsize_t chunk_rows) const;
  /// Extends a dataset by `rows` along its first dimension and writes them from `data`.
  void append_rows(const std::string& name, hid_t memory_type, hsize_t rows, const void* data) const;

  Dims shape(const std::string& name) const;
  bool is_integer(const std::string& name) const;
  /// The whole dataset, row-major, converted to double.
  std::vector<double> read_doubles(const std::string& name) const;
  /// Rows [first, first + count) along the first dimension, row-major, converted to double.
  std::vector<double> read_rows(const std::string& name, hsize_t first, hsize_t count) const;

 private:
  File(std::filesystem::path path, Id id) : path_(std::move(path)), id_(std::move(id)) {}
  Id open_dataset(const std::string& name) const;
  Id open_attribute(const std::string& object, const std::string& name) const;
  void replace_attribute(const std::string& object, const std::string& name, hid_t file_type, hid_t space,
                         hid_t memory_type, const void* data) const;

  std::filesystem::path path_;
  Id id_;
};

}  // namespace stoss::output::h5
