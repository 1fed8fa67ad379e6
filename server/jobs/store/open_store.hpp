#pragma once
/// @file Where the job store is (`--store sqlite:PATH` or `--store postgresql://...`) and opening it.

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "server/jobs/clock.hpp"
#include "server/jobs/store/store.hpp"

namespace stoss::server::jobs {

/// A parsed `--store` value.
struct StoreLocation {
  enum class Kind { sqlite, postgresql };
  Kind kind = Kind::sqlite;
  std::string target;  ///< the SQLite file, or the PostgreSQL URL as given

  /// `sqlite:PATH`, or the URL with its password shown as `***`.
  std::string describe() const;
};

/// Parses `sqlite:PATH` or `postgresql://USER[:PASSWORD]@HOST[:PORT]/DB` (also `postgres://`). Throws
/// StoreError naming the rule broken.
StoreLocation parse_store_location(const std::string& text);

/// The default store of a data directory: sqlite:DATA/jobs.db.
StoreLocation default_store_location(const std::filesystem::path& data);

/// The store could not be opened at start-up (bad URL, database unreachable, wrong credentials, schema
/// newer than this program); nothing was changed.
class StoreOpenError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Opens (creating and migrating) the store. Throws StoreOpenError with the reason.
std::unique_ptr<JobStore> open_store(const StoreLocation& location, const Clock& clock);

}  // namespace stoss::server::jobs
