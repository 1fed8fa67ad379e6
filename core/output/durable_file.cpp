#include "core/output/durable_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <string>
#include <system_error>

namespace stoss::output {

namespace fs = std::filesystem;

void sync_to_disk(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw std::system_error(errno, std::generic_category(), "cannot open " + path.string());
  const int status = ::fsync(fd);
  ::close(fd);
  if (status != 0) throw std::system_error(errno, std::generic_category(), "cannot sync " + path.string());
}

void rename_durably(const fs::path& from, const fs::path& to) {
  sync_to_disk(from);
  fs::rename(from, to);
  sync_to_disk(to.has_parent_path() ? to.parent_path() : fs::path("."));
}

}  // namespace stoss::output
