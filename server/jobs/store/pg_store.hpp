#pragma once
/// @file PgStore: the job store in a PostgreSQL database that API and worker processes on many hosts share.
/// Claims are one short statement with `FOR UPDATE SKIP LOCKED`; a queued job sends `NOTIFY stoss_jobs`,
/// which wakes idle workers listening in any process; the schema is versioned and migrates itself.

#include <memory>
#include <string>

#include "server/jobs/clock.hpp"
#include "server/jobs/store/store.hpp"

namespace stoss::server::jobs {

/// A JobStore in PostgreSQL. Times come from `clock` (every host's clock must be NTP-synchronised, as
/// leases compare times written by different hosts).
class PgStore : public JobStore {
 public:
  /// Connects to `url`, migrates the schema to the latest version and keeps at most `max_connections`
  /// connections. Throws StoreUnavailable when the server cannot be reached or refuses the credentials,
  /// StoreError when the database has a newer schema than this program knows.
  PgStore(const std::string& url, const Clock& clock, int max_connections = 8);
  ~PgStore() override;

  /// The schema version this program writes.
  static int latest_schema_version();
  /// The schema version of the database.
  int schema_version();
  /// The NOTIFY channel a queued job is announced on.
  static constexpr const char* channel = "stoss_jobs";
  /// The NOTIFY channel a cancel of a running job is announced on (payload: the job's id).
  static constexpr const char* cancel_channel = "stoss_cancel";

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
  /// LISTEN stoss_jobs and stoss_cancel on a connection of its own; reconnects (and calls `queued`) when
  /// it was lost.
  std::unique_ptr<Subscription> subscribe(StoreEvents events) override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stoss::server::jobs
