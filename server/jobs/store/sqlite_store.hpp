#pragma once
/// @file SqliteStore: the job store in one SQLite file (WAL, busy timeout, synchronous=FULL,
/// every write in BEGIN IMMEDIATE, a versioned schema that migrates itself on open).

#include <filesystem>
#include <memory>

#include "server/jobs/clock.hpp"
#include "server/jobs/store/store.hpp"

namespace stoss::server::jobs {

/// A JobStore in an SQLite database. Several processes may share the file; within one process,
/// connections are pooled and writes are serialised before they reach SQLite's lock.
class SqliteStore : public JobStore {
 public:
  /// Opens (creating) the database at `path` and migrates it to the latest schema.
  /// Throws sqlite::Error, also when the file has a newer schema than this program knows.
  SqliteStore(const std::filesystem::path& path, const Clock& clock, int busy_timeout_ms = 10000);
  ~SqliteStore() override;

  /// The schema version this program writes.
  static int latest_schema_version();
  /// The schema version of the open database.
  int schema_version();

  CreateResult create(const NewJob& job, int max_queued) override;
  std::optional<Job> get(const JobId& id) override;
  std::optional<nlohmann::json> scene(const JobId& id) override;
  Page list(std::optional<Status> status, int limit, std::optional<std::int64_t> cursor) override;
  std::optional<Job> claim(const std::string& worker, Millis lease, int max_ranks) override;
  Lease renew(const Claim& claim, Millis lease) override;
  bool progress(const Claim& claim, const Progress& p) override;
  bool finish(const Claim& claim, const Outcome& outcome) override;
  bool release(const Claim& claim) override;
  CancelResult request_cancel(const JobId& id) override;
  std::vector<Claim> expired(Millis now) override;
  Rescued requeue_expired(Millis now, int max_attempts) override;
  RemoveOutcome remove(const JobId& id) override;
  std::map<Status, std::int64_t> count_by_status() override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stoss::server::jobs
