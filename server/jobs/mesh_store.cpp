#include "server/jobs/mesh_store.hpp"

#include <cstdio>
#include <random>

#include "server/jobs/job_files.hpp"
#include "server/jobs/sha256.hpp"

namespace stoss::server::jobs {

namespace {

/// What the readers call the posted file in their messages ("request body:42: …").
constexpr const char* shown_name = "request body";

mesh::ImportedMesh read_as(const std::filesystem::path& path, const std::string& format) {
  return format == "msh" ? mesh::read_gmsh(path, shown_name) : mesh::read_abaqus(path, shown_name);
}

/// A name no other request uses at the same time: ".upload-<16 random hex digits>.<format>".
std::filesystem::path temporary_name(const std::filesystem::path& directory, const std::string& format) {
  static thread_local std::mt19937_64 random{std::random_device{}()};
  char digits[17];
  std::snprintf(digits, sizeof digits, "%016llx", static_cast<unsigned long long>(random()));
  return directory / (".upload-" + std::string(digits) + "." + format);
}

}  // namespace

std::string sniff_mesh_format(std::string_view bytes) {
  const std::size_t start = bytes.find_first_not_of(" \t\r\n");
  if (start == std::string_view::npos) return "";
  if (bytes.substr(start, 11) == "$MeshFormat") return "msh";
  if (bytes[start] == '*') return "inp";
  return "";
}

StoredMesh store_mesh(const std::filesystem::path& directory, std::string_view bytes, const std::string& format) {
  StoredMesh stored;
  stored.id = sha256_hex(bytes);
  for (const char* known : {"msh", "inp"}) {
    const auto path = directory / (stored.id + "." + known);
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) continue;
    stored.format = known;
    stored.mesh = read_as(path, known);
    return stored;
  }
  std::filesystem::create_directories(directory);
  const auto temporary = temporary_name(directory, format);
  try {
    write_synced(temporary, bytes);
    stored.mesh = read_as(temporary, format);
    std::filesystem::rename(temporary, directory / (stored.id + "." + format));
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
  stored.format = format;
  stored.created = true;
  return stored;
}

}  // namespace stoss::server::jobs
