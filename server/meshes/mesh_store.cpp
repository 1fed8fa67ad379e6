#include "server/meshes/mesh_store.hpp"

#include <malloc.h>

#include <algorithm>
#include <cstdio>
#include <random>

#include "core/output/durable_file.hpp"
#include "server/common/sha256.hpp"

namespace stoss::server::meshes {

namespace {

/// What the readers call the posted file in their messages ("request body:42: …").
constexpr const char* shown_name = "request body";
constexpr const char* formats[] = {"msh", "inp"};

/// A name no other request uses at the same time: ".upload-<16 random hex digits>.<format>".
std::filesystem::path temporary_name(const std::filesystem::path& directory, const std::string& format) {
  static thread_local std::mt19937_64 random{std::random_device{}()};
  char digits[17];
  std::snprintf(digits, sizeof digits, "%016llx", static_cast<unsigned long long>(random()));
  return directory / (".upload-" + std::string(digits) + "." + format);
}

/// Roughly what a parsed mesh holds in memory (for the cache's budget).
std::size_t memory_of(const mesh::ImportedMesh& m) {
  std::size_t bytes = 1024 + m.nodes.size() * (sizeof(Eigen::Vector3d) + sizeof(long)) +
                      m.hex8.size() * (sizeof(mesh::Hex) + 2 * sizeof(long));
  for (const auto& [name, members] : m.element_sets) bytes += 64 + name.size() + members.size() * sizeof(int);
  for (const auto& [name, faces] : m.surfaces)
    bytes += 64 + name.size() + faces.size() * sizeof(mesh::ElementFace);
  return bytes;
}

/// Parsing a large file leaves freed memory in glibc's arenas; give it back to the system.
ParsedMesh trimmed(mesh::ImportedMesh parsed, const std::string& id) {
  parsed.file = "mesh " + id;  // messages of later requests name the stored mesh, not the upload
  auto shared = std::make_shared<const mesh::ImportedMesh>(std::move(parsed));
  malloc_trim(0);
  return shared;
}

}  // namespace

MeshStoreFull::MeshStoreFull(std::uintmax_t u, std::uintmax_t s, std::uintmax_t l)
    : std::runtime_error("the mesh store holds " + std::to_string(u) + " bytes; " + std::to_string(s) +
                         " more would exceed the server limit max_mesh_store_bytes = " + std::to_string(l)),
      used(u),
      size(s),
      limit(l) {}

std::string sniff_mesh_format(std::string_view bytes) {
  const std::size_t start = bytes.find_first_not_of(" \t\r\n");
  if (start == std::string_view::npos) return "";
  if (bytes.substr(start, 11) == "$MeshFormat") return "msh";
  if (bytes[start] == '*') return "inp";
  return "";
}

bool is_mesh_id(const std::string& id) {
  return id.size() == 64 && std::all_of(id.begin(), id.end(), [](char c) {
           return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
         });
}

MeshStore& MeshStore::at(const std::filesystem::path& directory) {
  static std::mutex mutex;
  static std::map<std::filesystem::path, std::unique_ptr<MeshStore>> stores;
  std::lock_guard lock(mutex);
  auto& store = stores[directory.lexically_normal()];
  if (!store) store = std::make_unique<MeshStore>(directory);
  return *store;
}

std::optional<std::filesystem::path> MeshStore::path_of(const std::string& id) const {
  if (!is_mesh_id(id)) return std::nullopt;
  for (const char* format : formats) {
    const auto path = directory_ / (id + "." + format);
    std::error_code error;
    if (std::filesystem::is_regular_file(path, error)) return path;
  }
  return std::nullopt;
}

std::uintmax_t MeshStore::used_bytes() const {
  std::uintmax_t used = 0;
  std::error_code error;
  for (auto it = std::filesystem::directory_iterator(directory_, error);
       !error && it != std::filesystem::directory_iterator(); it.increment(error)) {
    const auto name = it->path().filename().string();
    if (name.size() != 68 || !is_mesh_id(name.substr(0, 64))) continue;
    std::error_code size_error;
    const auto size = it->file_size(size_error);
    if (!size_error) used += size;
  }
  return used;
}

template <class Parse>
ParsedMesh MeshStore::cached(const std::string& id, Parse parse) {
  std::unique_lock lock(cache_mutex_);
  if (auto it = cache_.find(id); it != cache_.end()) {
    it->second.used = ++clock_;
    auto future = it->second.parsed;
    lock.unlock();
    return future.get();  // rethrows the parse's error to the requests that waited for it
  }
  std::promise<ParsedMesh> promise;
  cache_[id] = Entry{promise.get_future().share(), 0, ++clock_};
  lock.unlock();
  try {
    ParsedMesh parsed = trimmed(parse(), id);
    promise.set_value(parsed);
    lock.lock();
    if (auto it = cache_.find(id); it != cache_.end() && it->second.bytes == 0) {
      it->second.bytes = memory_of(*parsed);
      cached_bytes_ += it->second.bytes;
      evict_locked();
    }
    return parsed;
  } catch (...) {
    promise.set_exception(std::current_exception());
    lock.lock();
    cache_.erase(id);  // a bad file is not remembered: nothing of it is stored
    throw;
  }
}

void MeshStore::evict_locked() {
  while (cached_bytes_ > cache_bytes) {
    auto oldest = cache_.end();
    for (auto it = cache_.begin(); it != cache_.end(); ++it)
      if (it->second.bytes > 0 && (oldest == cache_.end() || it->second.used < oldest->second.used))
        oldest = it;
    if (oldest == cache_.end()) return;
    cached_bytes_ -= oldest->second.bytes;
    cache_.erase(oldest);
  }
}

ParsedMesh MeshStore::parsed(const std::string& id, const mesh::ReadLimits& limits) {
  const auto path = path_of(id);
  if (!path) return nullptr;
  mesh::ReadLimits stored_limits = limits;
  stored_limits.includes = false;  // a stored mesh is self-contained
  return cached(id, [&] { return mesh::read_mesh_file(*path, "mesh " + id, stored_limits); });
}

StoredMesh MeshStore::store(std::string_view bytes, const std::string& format, const mesh::ReadLimits& limits,
                            std::uintmax_t max_store_bytes) {
  StoredMesh stored;
  stored.id = sha256_hex(bytes);
  const auto parse = [&] { return mesh::parse_mesh_bytes(bytes, format, shown_name, limits); };
  if (const auto path = path_of(stored.id)) {
    stored.format = path->extension().string().substr(1);
    stored.mesh = cached(stored.id, parse);  // the same bytes: parsed from the body, not re-read
    return stored;
  }
  stored.mesh = cached(stored.id, parse);  // an id names one content: a cached form is these bytes
  stored.format = format;
  std::lock_guard write(write_mutex_);
  if (path_of(stored.id)) return stored;  // stored by another request meanwhile
  const std::uintmax_t used = used_bytes();
  if (used + bytes.size() > max_store_bytes) throw MeshStoreFull(used, bytes.size(), max_store_bytes);
  std::filesystem::create_directories(directory_);
  const auto temporary = temporary_name(directory_, format);
  output::write_durably(directory_ / (stored.id + "." + format), bytes, temporary);
  stored.created = true;
  return stored;
}

bool MeshStore::remove(const std::string& id) {
  std::lock_guard write(write_mutex_);
  bool removed = false;
  if (is_mesh_id(id))
    for (const char* format : formats) {
      std::error_code error;
      removed = std::filesystem::remove(directory_ / (id + "." + format), error) || removed;
    }
  std::lock_guard lock(cache_mutex_);
  if (auto it = cache_.find(id); it != cache_.end() && it->second.bytes > 0) {
    cached_bytes_ -= it->second.bytes;
    cache_.erase(it);
  }
  return removed;
}

}  // namespace stoss::server::meshes
