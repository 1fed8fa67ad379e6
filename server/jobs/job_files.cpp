#include "server/jobs/job_files.hpp"

#include <fcntl.h>
#include <unistd.h>

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

void JobFiles::prepare_attempt(const JobId& id) const {
  std::filesystem::create_directories(dir(id));
  discard_partial(id);
  std::error_code ignored;
  std::filesystem::remove(result(id), ignored);
  std::filesystem::remove(xdmf(id), ignored);
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
  {
    std::ofstream out(study_partial(id), std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out)
      throw std::system_error(EIO, std::generic_category(), "cannot write " + study_partial(id).string());
  }
  sync_to_disk(study_partial(id));
  std::filesystem::rename(study_partial(id), study(id));
  sync_to_disk(dir(id));
}

void JobFiles::remove(const JobId& id) const {
  std::error_code ignored;
  std::filesystem::remove_all(dir(id), ignored);
}

}  // namespace stoss::server::jobs
