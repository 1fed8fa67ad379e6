#pragma once
/// @file JobStore: the state of the queue (what exists, who runs what, how it ended), behind one seam.
/// SQLite implements it (sqlite_store.hpp, one host) and PostgreSQL (pg_store.hpp, many hosts).

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "server/jobs/job.hpp"

namespace stoss::server::jobs {

/// The store cannot do what was asked; the message says why.
class StoreError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The store is away for now (its database server is down or restarting): nothing was changed, and the
/// same call may succeed later. The HTTP layer answers 503 with Retry-After.
class StoreUnavailable : public StoreError {
 public:
  using StoreError::StoreError;
};

/// While it lives, a store calls back about changes other processes made (StoreEvents); destroying it
/// stops the calls.
class Subscription {
 public:
  virtual ~Subscription() = default;
};

/// What a store tells a process about changes other processes made.
struct StoreEvents {
  std::function<void()> queued;  ///< a job may have been queued (also after a lost connection came back)
  std::function<void(const JobId&)> cancel_requested;  ///< a cancel was posted for job `id`, which runs
};

/// The MPI ranks `scene` asks for (solver.ranks), 1 when it does not say: what the store keeps as Job::ranks
/// at submission.
int scene_ranks(const nlohmann::json& scene);

/// What POST /v1/jobs (or POST /v1/studies) asks the store to keep (Job::ranks comes from the scene).
struct NewJob {
  std::optional<std::string> idempotency_key;
  std::string body_hash;  ///< of the whole request body: a key reused with another body is a conflict
  nlohmann::json scene;
  std::vector<std::string> effects;
  Progress progress;  ///< step 0 of `steps`
  Kind kind = Kind::simulation;
  std::optional<nlohmann::json> study;  ///< a study's parameters (set for Kind::study only)
};

struct CreateResult {
  enum class Outcome {
    created,       ///< committed (durably) as a new queued job
    existing,      ///< same idempotency key and body: the original job
    key_conflict,  ///< same idempotency key, different body
    queue_full     ///< max_queued jobs already wait
  };
  Outcome outcome;
  std::optional<Job> job;  ///< set for created and existing
};

/// One page of a newest-first listing.
struct Page {
  std::vector<Job> jobs;
  std::optional<std::int64_t> next_cursor;  ///< pass back as `cursor` for the next page
};

/// How a claimed run ended, as the worker reports it.
struct Outcome {
  Status status = Status::failed;  ///< succeeded, failed or canceled
  std::optional<nlohmann::json> summary;
  std::optional<std::string> error;
  /// The attempt whose folder holds the run's files, when it is not the reporting attempt: an earlier
  /// attempt's run that completed but could not be reported (its lease lapsed), adopted instead of rerun.
  std::optional<int> result_attempt = std::nullopt;
};

/// One claimed attempt of a running job: the worker that holds its lease and the attempt number its claim
/// made. A call naming a claim changes the job only while the store still names both, so an attempt that
/// lost its lease (rescued, claimed again: a higher attempt) is fenced out, even under the same worker name.
struct Claim {
  JobId id;
  std::string worker;
  int attempt = 0;
};

/// The claim that `job`, as JobStore::claim returned it, holds.
inline Claim claim_of(const Job& job) {
  return {job.id, job.worker.value_or(""), job.attempt};
}

/// What a lease renewal found.
enum class Lease {
  held,              ///< renewed
  cancel_requested,  ///< renewed, and the user asked to cancel
  lost               ///< the job is no longer this worker's (rescued, deleted): stop without reporting
};

struct CancelResult {
  enum class Outcome {
    canceled,      ///< was queued: canceled at once
    requested,     ///< is running: the worker will stop within a step
    already_done,  ///< succeeded or failed: nothing to cancel
    not_found
  };
  Outcome outcome;
  std::optional<Job> job;  ///< the job after the call (unset when not_found)
};

enum class RemoveOutcome { removed, not_finished, not_found };

/// What one pass of the rescuer did to running jobs whose lease had expired.
struct Rescued {
  int adopted = 0;   ///< the run had completed: its outcome reported for the worker that could not
  int requeued = 0;  ///< back to queued for another attempt
  int failed = 0;    ///< out of attempts
  int canceled = 0;  ///< cancel had been requested
  int total() const { return adopted + requeued + failed + canceled; }
};

/// The job queue's state. Every method is one transaction and safe to call from any thread.
/// Workers are named by an opaque string; a worker may change a job only while it holds the lease.
class JobStore {
 public:
  virtual ~JobStore() = default;

  /// Queues a job unless the key was seen before or `max_queued` jobs are queued already.
  virtual CreateResult create(const NewJob& job, int max_queued) = 0;
  /// The job without its scene (Job::scene is null; see scene()).
  virtual std::optional<Job> get(const JobId& id) = 0;
  /// The scene of job `id` as submitted, or nullopt for an unknown job.
  virtual std::optional<nlohmann::json> scene(const JobId& id) = 0;
  /// Newest first; `cursor` continues a previous page.
  virtual Page list(std::optional<Status> status, int limit, std::optional<std::int64_t> cursor) = 0;

  /// Takes the oldest queued job that asks for at most `max_ranks` MPI ranks (Job::ranks): running,
  /// attempt + 1, lease until now + `lease`. A job asking for more stays queued for a worker that has them.
  virtual std::optional<Job> claim(const std::string& worker, Millis lease, int max_ranks) = 0;
  /// Extends the lease to now + `lease` if `claim` still holds it.
  virtual Lease renew(const Claim& claim, Millis lease) = 0;
  /// Records progress; false when the lease is lost.
  virtual bool progress(const Claim& claim, const Progress& p) = 0;
  /// Records the end of a run and publishes its files (Job::result_attempt: outcome.result_attempt, else the
  /// claim's attempt), in one transaction that changes nothing (false) unless `claim` still holds the lease.
  virtual bool finish(const Claim& claim, const Outcome& outcome) = 0;
  /// Gives a running job back to the queue without counting the attempt (graceful shutdown).
  virtual bool release(const Claim& claim) = 0;

  /// Cancels a queued job at once; flags a running one for its worker.
  virtual CancelResult request_cancel(const JobId& id) = 0;
  /// The claims of running jobs whose lease ended before `now` (the rescuer adopts those whose run
  /// completed).
  virtual std::vector<Claim> expired(Millis now) = 0;
  /// Running jobs whose lease ended before `now`: requeued while attempt < max_attempts,
  /// otherwise failed with the reason; canceled if cancel had been requested.
  virtual Rescued requeue_expired(Millis now, int max_attempts) = 0;
  /// Deletes a finished job's record (its files are the caller's business).
  virtual RemoveOutcome remove(const JobId& id) = 0;

  /// Number of jobs in each status (every status present, possibly 0).
  virtual std::map<Status, std::int64_t> count_by_status() = 0;

  /// The queued and running jobs whose scene names stored mesh `mesh_id` ("mesh": {"id": ...} of a body),
  /// for DELETE /v1/meshes/{id}. This default pages through list() and reads each such job's scene.
  virtual std::vector<JobId> active_jobs_using_mesh(const std::string& mesh_id);

  /// Calls `events` (from a thread of the store's) when another process may have queued a job (and after a
  /// lost connection came back) or asked to cancel a running one. Returns nullptr when the store has no
  /// such signal: then workers poll for jobs, and see a cancel at their next lease renewal.
  virtual std::unique_ptr<Subscription> subscribe(StoreEvents events) { return nullptr; }
};

}  // namespace stoss::server::jobs
