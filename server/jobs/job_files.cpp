#include "server/jobs/job_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <fstream>
#include <system_error>

namespace stoss::server::jobs {

namespace {

/// fsync of a file or directory, so that a rename after it cannot expose a torn file.
void sync_to_disk(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw std::system_error(errno, std::generic_category(), "cannot open " + path.string());
  const int status = ::fsync(fd);
  ::close(fd);
  if (status != 0) throw std::system_error(errno, std::generic_category(), "cannot sync " + path.string());
}

}  // namespace

void write_synced(const std::filesystem::path& path, std::string_view bytes) {
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) throw std::system_error(EIO, std::generic_category(), "cannot write " + path.string());
  }
  sync_to_disk(path);
}

std::optional<std::filesystem::path> JobFiles::stored_mesh(const std::string& id) const {
  const bool hex = id.size() == 64 &&
                   std::all_of(id.begin(), id.end(), [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
  if (!hex) return std::nullopt;
  for (const char* extension : {".msh", ".inp"}) {
    const std::filesystem::path path = meshes_ / (id + extension);
    std::error_code error;
    if (std::filesystem::is_regular_file(path, error)) return path;
  }
  return std::nullopt;
}

scene::MeshFiles JobFiles::mesh_files() const {
  return {std::nullopt, [files = *this](const std::string& id) { return files.stored_mesh(id); }};
}

void JobFiles::prepare_attempt(const JobId& id) const {
  std::filesystem::create_directories(dir(id));
  discard_partial(id);
  std::error_code ignored;
  std::filesystem::remove(result(id), ignored);
  std::filesystem::remove(xdmf(id), ignored);
  std::filesystem::remove(xdmf_mesh(id), ignored);
  std::filesystem::remove(study(id), ignored);
  std::filesystem::remove(dir(id) / "series.partial.jsonl", ignored);
}

void JobFiles::discard_partial(const JobId& id) const {
  std::error_code ignored;
  std::filesystem::remove(dir(id) / output::partial_file_name, ignored);
  std::filesystem::remove(dir(id) / output::incomplete_file_name, ignored);
  std::filesystem::remove(study_partial(id), ignored);
}

void JobFiles::write_study(const JobId& id, const std::string& text) const {
  write_synced(study_partial(id), text);
  std::filesystem::rename(study_partial(id), study(id));
  sync_to_disk(dir(id));
}

void JobFiles::remove(const JobId& id) const {
  std::error_code ignored;
  std::filesystem::remove_all(dir(id), ignored);
}

}  // namespace stoss::server::jobs
