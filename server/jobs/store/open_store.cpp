#include "server/jobs/store/open_store.hpp"

#include "server/jobs/store/pg.hpp"
#include "server/jobs/store/pg_store.hpp"
#include "server/jobs/store/sqlite_store.hpp"

namespace stoss::server::jobs {

std::string StoreLocation::describe() const {
  return kind == Kind::sqlite ? "sqlite:" + target : pg::redacted(target);
}

StoreLocation parse_store_location(const std::string& text) {
  if (text.rfind("sqlite:", 0) == 0) {
    const std::string path = text.substr(7);
    if (path.empty()) throw StoreError("--store sqlite:PATH needs a file name after 'sqlite:'");
    return {StoreLocation::Kind::sqlite, path};
  }
  if (text.rfind("postgresql://", 0) == 0 || text.rfind("postgres://", 0) == 0) {
    pg::check_url(text);
    return {StoreLocation::Kind::postgresql, text};
  }
  throw StoreError("--store needs sqlite:PATH or postgresql://USER[:PASSWORD]@HOST:PORT/DB, got '" +
                   pg::redacted(text) + "'");
}

StoreLocation default_store_location(const std::filesystem::path& data) {
  return {StoreLocation::Kind::sqlite, (data / "jobs.db").string()};
}

std::unique_ptr<JobStore> open_store(const StoreLocation& location, const Clock& clock) {
  try {
    if (location.kind == StoreLocation::Kind::postgresql)
      return std::make_unique<PgStore>(location.target, clock);
    const std::filesystem::path path(location.target);
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    return std::make_unique<SqliteStore>(path, clock);
  } catch (const std::exception& e) {
    throw StoreOpenError("cannot open the job store " + location.describe() + ": " + e.what());
  }
}

}  // namespace stoss::server::jobs
