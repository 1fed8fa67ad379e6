#pragma once
/// @file The meshes posted to /v1/meshes (docs/api.md, "Meshes"): stored once under DIR/meshes as
/// <sha256 of the bytes>.msh or .inp, content-addressed and never changed, so that a job naming a mesh by
/// id is reproducible from its stored scene. A stored mesh is self-contained (no *INCLUDE), so its id fixes
/// its content. Paths are built only from the hex digest. Each mesh is parsed once per process: later
/// requests naming its id share the parsed form (MeshStore::parsed).

#include <cstdint>
#include <filesystem>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/mesh/mesh_file.hpp"

namespace stoss::server::meshes {

using ParsedMesh = std::shared_ptr<const mesh::ImportedMesh>;

/// A stored mesh: its id, format ("msh" | "inp"), the parsed content, and whether this call stored it.
struct StoredMesh {
  std::string id;
  std::string format;
  ParsedMesh mesh;
  bool created = false;
};

/// Storing the bytes would take the store above --max-mesh-store-bytes (answered 413, docs/api.md).
class MeshStoreFull : public std::runtime_error {
 public:
  MeshStoreFull(std::uintmax_t used, std::uintmax_t size, std::uintmax_t limit);
  std::uintmax_t used, size, limit;
};

/// "msh" when `bytes` start (after blanks) with $MeshFormat, "inp" when with '*' (a keyword or comment
/// line of a deck); "" when neither.
std::string sniff_mesh_format(std::string_view bytes);

/// Whether `id` is 64 lowercase hex digits (what sha256_hex gives).
bool is_mesh_id(const std::string& id);

class MeshStore {
 public:
  /// The store of `directory` in this process: one per directory, shared by every request.
  static MeshStore& at(const std::filesystem::path& directory);

  explicit MeshStore(std::filesystem::path directory) : directory_(std::move(directory)) {}

  /// Parses `bytes` as a mesh file of `format` under `limits` (nothing but the bytes is read) and stores
  /// them (created when missing): written to a temporary name, synced, renamed to <id>.<format>. Bytes
  /// stored before are not written again (created = false).
  /// @throws mesh::MeshFileError naming "request body" and the line (or element) when the file is not a
  ///         usable mesh; MeshStoreFull when the store would exceed `max_store_bytes`; std::system_error
  ///         when the file cannot be written.
  StoredMesh store(std::string_view bytes, const std::string& format, const mesh::ReadLimits& limits,
                   std::uintmax_t max_store_bytes);

  /// The parsed content of stored mesh `id` (its messages name it "mesh <id>"), parsed at most once while
  /// it stays in the cache (cache_bytes, least recently used out first); requests that ask at the same time
  /// wait for one parse. nullptr when no mesh has the id. @throws mesh::MeshFileError when the stored
  /// file is not usable under `limits` (e.g. stored by an older server, with *INCLUDE).
  ParsedMesh parsed(const std::string& id, const mesh::ReadLimits& limits);

  /// Removes mesh `id` (file and cached form); false when there is none.
  bool remove(const std::string& id);

  /// The stored file of `id`, nullopt when none.
  std::optional<std::filesystem::path> path_of(const std::string& id) const;

  /// Bytes of every stored mesh file (the directory as it is now, other processes' uploads included).
  std::uintmax_t used_bytes() const;

  /// Memory the parsed forms may hold before the least recently used one is dropped.
  static constexpr std::size_t cache_bytes = std::size_t(256) << 20;

 private:
  struct Entry {
    std::shared_future<ParsedMesh> parsed;
    std::size_t bytes = 0;  ///< 0 while the parse runs
    std::uint64_t used = 0;
  };
  /// The cached form of `id`, or `parse()` run once (others asking meanwhile wait for it).
  template <class Parse>
  ParsedMesh cached(const std::string& id, Parse parse);
  void evict_locked();

  std::filesystem::path directory_;
  mutable std::mutex cache_mutex_;
  std::map<std::string, Entry> cache_;
  std::size_t cached_bytes_ = 0;
  std::uint64_t clock_ = 0;
  std::mutex write_mutex_;  ///< quota check and rename, removal: one at a time
};

}  // namespace stoss::server::meshes
