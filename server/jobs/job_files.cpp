#include "server/jobs/job_files.hpp"

namespace stoss::server::jobs {

void JobFiles::prepare_attempt(const JobId& id) const {
  std::filesystem::create_directories(dir(id));
  discard_partial(id);
  std::error_code ignored;
  std::filesystem::remove(result(id), ignored);
  std::filesystem::remove(xdmf(id), ignored);
}

void JobFiles::discard_partial(const JobId& id) const {
  std::error_code ignored;
  std::filesystem::remove(dir(id) / output::partial_file_name, ignored);
  std::filesystem::remove(dir(id) / output::incomplete_file_name, ignored);
}

void JobFiles::remove(const JobId& id) const {
  std::error_code ignored;
  std::filesystem::remove_all(dir(id), ignored);
}

}  // namespace stoss::server::jobs
