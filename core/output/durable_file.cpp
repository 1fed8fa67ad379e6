#include "core/output/durable_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
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

void write_durably(const fs::path& path, std::string_view bytes, const fs::path& temporary) {
  const fs::path written = temporary.empty() ? fs::path(path.string() + ".tmp") : temporary;
  try {
    {
      std::ofstream out(written, std::ios::binary | std::ios::trunc);
      out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      out.flush();
      if (!out) throw std::system_error(EIO, std::generic_category(), "cannot write " + written.string());
    }
    rename_durably(written, path);
  } catch (...) {
    std::error_code ignored;
    fs::remove(written, ignored);
    throw;
  }
}

}  // namespace stoss::output
