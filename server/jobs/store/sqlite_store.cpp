#include "server/jobs/store/sqlite_store.hpp"

#include <mutex>
#include <vector>

#include "server/jobs/store/sqlite.hpp"

namespace stoss::server::jobs {

namespace {

using sqlite::Connection;
using sqlite::Statement;
using sqlite::Transaction;

/// Schema migrations, in order; migration i brings the database to version i + 1. Never edit one
/// that has shipped: append a new one.
const std::vector<std::string> migrations = {
    // 1: the jobs table.
    R"sql(
    CREATE TABLE jobs (
      seq              INTEGER PRIMARY KEY AUTOINCREMENT,
      id               TEXT    NOT NULL UNIQUE CHECK (length(id) = 32),
      status           TEXT    NOT NULL
                       CHECK (status IN ('queued', 'running', 'succeeded', 'failed', 'canceled')),
      created_ms       INTEGER NOT NULL,
      started_ms       INTEGER,
      finished_ms      INTEGER,
      attempt          INTEGER NOT NULL DEFAULT 0,
      worker           TEXT,
      lease_expires_ms INTEGER,
      cancel_requested INTEGER NOT NULL DEFAULT 0,
      idempotency_key  TEXT UNIQUE,
      body_hash        TEXT    NOT NULL,
      scene            TEXT    NOT NULL,
      effects          TEXT    NOT NULL,
      progress_step    INTEGER NOT NULL DEFAULT 0,
      progress_steps   INTEGER NOT NULL DEFAULT 0,
      progress_time    REAL    NOT NULL DEFAULT 0,
      progress_end     REAL    NOT NULL DEFAULT 0,
      progress_eta     REAL,
      summary          TEXT,
      error            TEXT
    );
    CREATE INDEX jobs_by_status ON jobs (status, seq);
    )sql",
    // 2: the rescuer looks running jobs up by lease expiry.
    R"sql(
    CREATE INDEX jobs_by_lease ON jobs (status, lease_expires_ms);
    )sql",
    // 3: study jobs. Every job that existed before is a simulation.
    R"sql(
    ALTER TABLE jobs ADD COLUMN kind TEXT NOT NULL DEFAULT 'simulation'
                     CHECK (kind IN ('simulation', 'study'));
    ALTER TABLE jobs ADD COLUMN study TEXT;
    )sql",
    // 4: the scene's name, shown with the job (the scene itself is read only by workers).
    R"sql(
    ALTER TABLE jobs ADD COLUMN name TEXT;
    UPDATE jobs SET name = json_extract(scene, '$.name')
     WHERE json_valid(scene) AND json_type(scene, '$.name') = 'text';
    )sql",
    // 5: each attempt writes in a folder of its own; a finished job names the one it published.
    R"sql(
    ALTER TABLE jobs ADD COLUMN result_attempt INTEGER;
    )sql",
    // 6: the MPI ranks a job asks for (its scene's solver.ranks); a claim takes only jobs within the
    // worker's --ranks-per-job. Every job that existed before asks for one.
    R"sql(
    ALTER TABLE jobs ADD COLUMN ranks INTEGER NOT NULL DEFAULT 1 CHECK (ranks >= 1);
    )sql",
};

/// Every column but `scene` (scenes can be megabytes; only a worker needs one).
const std::string job_columns =
    "seq, id, status, created_ms, started_ms, finished_ms, attempt, worker, lease_expires_ms, "
    "cancel_requested, idempotency_key, body_hash, effects, progress_step, progress_steps, progress_time, "
    "progress_end, progress_eta, summary, error, kind, study, name, result_attempt, ranks";

Status status_column(const Statement& s, int col) {
  auto status = parse_status(s.text(col));
  if (!status) throw sqlite::Error("job store: unknown status '" + s.text(col) + "'");
  return *status;
}

std::optional<nlohmann::json> json_column(const Statement& s, int col) {
  auto text = s.optional_text(col);
  if (!text) return std::nullopt;
  return nlohmann::json::parse(*text);
}

/// Reads a row selected with `job_columns` (plus `scene` as the next column when `with_scene`).
Job read_job(const Statement& s, bool with_scene = false) {
  Job job;
  job.seq = s.int64(0);
  auto id = JobId::parse(s.text(1));
  if (!id) throw sqlite::Error("job store: malformed id '" + s.text(1) + "'");
  job.id = *id;
  job.status = status_column(s, 2);
  job.created = s.int64(3);
  job.started = s.optional_int64(4);
  job.finished = s.optional_int64(5);
  job.attempt = static_cast<int>(s.int64(6));
  job.worker = s.optional_text(7);
  job.lease_expires = s.optional_int64(8);
  job.cancel_requested = s.int64(9) != 0;
  job.idempotency_key = s.optional_text(10);
  job.body_hash = s.text(11);
  job.effects = nlohmann::json::parse(s.text(12)).get<std::vector<std::string>>();
  job.progress = {static_cast<int>(s.int64(13)), static_cast<int>(s.int64(14)), s.real(15), s.real(16),
                  s.optional_real(17)};
  job.summary = json_column(s, 18);
  job.error = s.optional_text(19);
  auto kind = parse_kind(s.text(20));
  if (!kind) throw sqlite::Error("job store: unknown kind '" + s.text(20) + "'");
  job.kind = *kind;
  job.study = json_column(s, 21);
  job.name = s.optional_text(22);
  if (auto attempt = s.optional_int64(23)) job.result_attempt = static_cast<int>(*attempt);
  job.ranks = static_cast<int>(s.int64(24));
  if (with_scene) job.scene = nlohmann::json::parse(s.text(25));
  return job;
}

/// The WHERE clause of a call naming a claim, its parameters ?1 (id), ?2 (worker) and ?3 (attempt).
const std::string held_by_claim = " WHERE id = ?1 AND worker = ?2 AND attempt = ?3 AND status = 'running'";

/// Binds a claim to ?1, ?2 and ?3 of held_by_claim.
Statement& bind_claim(Statement& s, const Claim& claim) {
  return s.bind(1, claim.id.str()).bind(2, claim.worker).bind(3, claim.attempt);
}

std::optional<Job> select_job(Connection& c, const JobId& id) {
  Statement s(c, "SELECT " + job_columns + " FROM jobs WHERE id = ?1");
  s.bind(1, id.str());
  if (!s.step()) return std::nullopt;
  return read_job(s);
}

int current_version(Connection& c) {
  Statement s(c, "SELECT coalesce(max(version), 0) FROM schema_version");
  s.step();
  return static_cast<int>(s.int64(0));
}

/// Brings the database to the latest schema in one transaction.
void migrate(Connection& c, Millis now) {
  Transaction tx(c);
  c.exec(
      "CREATE TABLE IF NOT EXISTS schema_version (version INTEGER PRIMARY KEY, applied_ms INTEGER NOT NULL)");
  const int version = current_version(c);
  const int latest = static_cast<int>(migrations.size());
  if (version > latest)
    throw sqlite::Error("job store: database schema version " + std::to_string(version) +
                        " is newer than this program's (" + std::to_string(latest) + ")");
  for (int v = version + 1; v <= latest; ++v) {
    c.exec(migrations[v - 1]);
    Statement(c, "INSERT INTO schema_version (version, applied_ms) VALUES (?1, ?2)")
        .bind(1, v)
        .bind(2, now)
        .run();
  }
  tx.commit();
}

std::string pragma_value(Connection& c, const std::string& pragma) {
  Statement s(c, "PRAGMA " + pragma);
  return s.step() ? s.text(0) : std::string();
}

}  // namespace

struct SqliteStore::Impl {
  std::filesystem::path path;
  const Clock& clock;
  int busy_timeout_ms;
  std::mutex pool_mutex;
  std::vector<std::unique_ptr<Connection>> idle;
  std::mutex write_mutex;  ///< one writer at a time in this process; SQLite's lock covers other processes

  std::unique_ptr<Connection> open() {
    auto c = std::make_unique<Connection>(path, busy_timeout_ms);
    c->exec("PRAGMA synchronous = FULL; PRAGMA foreign_keys = ON;");
    return c;
  }

  /// A pooled connection, returned to the pool when the borrower goes out of scope.
  struct Borrowed {
    Impl& impl;
    std::unique_ptr<Connection> connection;
    ~Borrowed() {
      std::lock_guard lock(impl.pool_mutex);
      impl.idle.push_back(std::move(connection));
    }
    Connection& operator*() { return *connection; }
    Connection* operator->() { return connection.get(); }
  };

  Borrowed borrow() {
    std::unique_ptr<Connection> c;
    {
      std::lock_guard lock(pool_mutex);
      if (!idle.empty()) {
        c = std::move(idle.back());
        idle.pop_back();
      }
    }
    return Borrowed{*this, c ? std::move(c) : open()};
  }
};

SqliteStore::SqliteStore(const std::filesystem::path& path, const Clock& clock, int busy_timeout_ms)
    : impl_(new Impl{path, clock, busy_timeout_ms, {}, {}, {}}) {
  auto c = impl_->open();
  if (pragma_value(*c, "journal_mode = WAL") != "wal")
    throw sqlite::Error("job store: cannot switch " + path.string() + " to WAL mode");
  migrate(*c, clock.now());
  std::lock_guard lock(impl_->pool_mutex);
  impl_->idle.push_back(std::move(c));
}

SqliteStore::~SqliteStore() = default;

int SqliteStore::latest_schema_version() {
  return static_cast<int>(migrations.size());
}

int SqliteStore::schema_version() {
  auto c = impl_->borrow();
  return current_version(*c);
}

CreateResult SqliteStore::create(const NewJob& job, int max_queued) {
  std::lock_guard write(impl_->write_mutex);
  auto c = impl_->borrow();
  Transaction tx(*c);
  if (job.idempotency_key) {
    Statement s(*c, "SELECT " + job_columns + " FROM jobs WHERE idempotency_key = ?1");
    s.bind(1, *job.idempotency_key);
    if (s.step()) {
      Job existing = read_job(s);
      const bool same_body = existing.body_hash == job.body_hash;
      return {same_body ? CreateResult::Outcome::existing : CreateResult::Outcome::key_conflict, existing};
    }
  }
  Statement count(*c, "SELECT count(*) FROM jobs WHERE status = 'queued'");
  count.step();
  if (count.int64(0) >= max_queued) return {CreateResult::Outcome::queue_full, std::nullopt};

  Statement insert(*c,
                   "INSERT INTO jobs (id, status, created_ms, idempotency_key, body_hash, scene, effects, "
                   "progress_steps, progress_end, kind, study, name, ranks)"
                   " VALUES (?1, 'queued', ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12)"
                   " RETURNING " +
                       job_columns);
  insert.bind(1, JobId::random().str())
      .bind(2, impl_->clock.now())
      .bind(3, job.idempotency_key)
      .bind(4, job.body_hash)
      .bind(5, job.scene.dump())
      .bind(6, nlohmann::json(job.effects).dump())
      .bind(7, job.progress.steps)
      .bind(8, job.progress.end)
      .bind(9, to_string(job.kind))
      .bind(10, job.study ? std::optional(job.study->dump()) : std::nullopt)
      .bind(11, job.scene.is_object() && job.scene.contains("name") && job.scene["name"].is_string()
                    ? std::optional(job.scene["name"].get<std::string>())
                    : std::nullopt)
      .bind(12, scene_ranks(job.scene));
  insert.step();
  Job created = read_job(insert);
  insert.run();
  tx.commit();
  return {CreateResult::Outcome::created, created};
}

std::optional<Job> SqliteStore::get(const JobId& id) {
  auto c = impl_->borrow();
  return select_job(*c, id);
}

std::optional<nlohmann::json> SqliteStore::scene(const JobId& id) {
  auto c = impl_->borrow();
  Statement s(*c, "SELECT scene FROM jobs WHERE id = ?1");
  s.bind(1, id.str());
  if (!s.step()) return std::nullopt;
  return nlohmann::json::parse(s.text(0));
}

Page SqliteStore::list(std::optional<Status> status, int limit, std::optional<std::int64_t> cursor) {
  auto c = impl_->borrow();
  Statement s(*c, "SELECT " + job_columns +
                      " FROM jobs WHERE (?1 IS NULL OR status = ?1) AND (?2 IS NULL OR seq < ?2)"
                      " ORDER BY seq DESC LIMIT ?3");
  s.bind(1, status ? std::optional(to_string(*status)) : std::nullopt).bind(2, cursor).bind(3, limit + 1);
  Page page;
  while (s.step()) page.jobs.push_back(read_job(s));
  if (static_cast<int>(page.jobs.size()) > limit) {
    page.jobs.pop_back();
    page.next_cursor = page.jobs.back().seq;
  }
  return page;
}

std::optional<Job> SqliteStore::claim(const std::string& worker, Millis lease, int max_ranks) {
  std::lock_guard write(impl_->write_mutex);
  auto c = impl_->borrow();
  Transaction tx(*c);
  const Millis now = impl_->clock.now();
  Statement s(
      *c,
      "UPDATE jobs SET status = 'running', worker = ?1, attempt = attempt + 1, lease_expires_ms = ?2,"
      " started_ms = ?3, progress_step = 0, progress_time = 0, progress_eta = NULL"
      " WHERE seq = (SELECT seq FROM jobs WHERE status = 'queued' AND ranks <= ?4 ORDER BY seq LIMIT 1)"
      " RETURNING " +
          job_columns + ", scene");
  s.bind(1, worker).bind(2, now + lease).bind(3, now).bind(4, max_ranks);
  if (!s.step()) return std::nullopt;
  Job job = read_job(s, true);
  s.run();
  tx.commit();
  return job;
}

Lease SqliteStore::renew(const Claim& claim, Millis lease) {
  std::lock_guard write(impl_->write_mutex);
  auto c = impl_->borrow();
  Transaction tx(*c);
  Statement s(*c, "UPDATE jobs SET lease_expires_ms = ?4" + held_by_claim + " RETURNING cancel_requested");
  bind_claim(s, claim).bind(4, impl_->clock.now() + lease);
  if (!s.step()) return Lease::lost;
  const bool cancel = s.int64(0) != 0;
  s.run();
  tx.commit();
  return cancel ? Lease::cancel_requested : Lease::held;
}

bool SqliteStore::progress(const Claim& claim, const Progress& p) {
  std::lock_guard write(impl_->write_mutex);
  auto c = impl_->borrow();
  Transaction tx(*c);
  Statement s(
      *c,
      "UPDATE jobs SET progress_step = ?4, progress_steps = ?5, progress_time = ?6, progress_end = ?7,"
      " progress_eta = ?8" +
          held_by_claim);
  bind_claim(s, claim)
      .bind(4, p.step)
      .bind(5, p.steps)
      .bind(6, p.time)
      .bind(7, p.end)
      .bind(8, p.eta_seconds)
      .run();
  const bool held = c->changes() == 1;
  tx.commit();
  return held;
}

bool SqliteStore::finish(const Claim& claim, const Outcome& outcome) {
  std::lock_guard write(impl_->write_mutex);
  auto c = impl_->borrow();
  Transaction tx(*c);
  Statement s(
      *c,
      "UPDATE jobs SET status = ?4, summary = ?5, error = ?6, finished_ms = ?7, lease_expires_ms = NULL,"
      " progress_eta = NULL, result_attempt = ?8" +
          held_by_claim);
  bind_claim(s, claim)
      .bind(4, to_string(outcome.status))
      .bind(5, outcome.summary ? std::optional(outcome.summary->dump()) : std::nullopt)
      .bind(6, outcome.error)
      .bind(7, impl_->clock.now())
      .bind(8, outcome.result_attempt.value_or(claim.attempt))
      .run();
  const bool held = c->changes() == 1;
  tx.commit();
  return held;
}

bool SqliteStore::release(const Claim& claim) {
  std::lock_guard write(impl_->write_mutex);
  auto c = impl_->borrow();
  Transaction tx(*c);
  Statement s(*c,
              "UPDATE jobs SET status = 'queued', worker = NULL, lease_expires_ms = NULL, started_ms = NULL,"
              " attempt = attempt - 1, progress_step = 0, progress_time = 0, progress_eta = NULL" +
                  held_by_claim);
  bind_claim(s, claim).run();
  const bool held = c->changes() == 1;
  tx.commit();
  return held;
}

CancelResult SqliteStore::request_cancel(const JobId& id) {
  std::lock_guard write(impl_->write_mutex);
  auto c = impl_->borrow();
  Transaction tx(*c);
  auto job = select_job(*c, id);
  if (!job) return {CancelResult::Outcome::not_found, std::nullopt};
  CancelResult::Outcome outcome = CancelResult::Outcome::already_done;
  if (job->status == Status::queued) {
    Statement(*c, "UPDATE jobs SET status = 'canceled', cancel_requested = 1, finished_ms = ?1 WHERE id = ?2")
        .bind(1, impl_->clock.now())
        .bind(2, id.str())
        .run();
    outcome = CancelResult::Outcome::canceled;
  } else if (job->status == Status::running) {
    Statement(*c, "UPDATE jobs SET cancel_requested = 1 WHERE id = ?1").bind(1, id.str()).run();
    outcome = CancelResult::Outcome::requested;
  } else if (job->status == Status::canceled) {
    outcome = CancelResult::Outcome::canceled;
  }
  job = select_job(*c, id);
  tx.commit();
  return {outcome, job};
}

std::vector<Claim> SqliteStore::expired(Millis now) {
  auto c = impl_->borrow();
  Statement s(*c, "SELECT id, worker, attempt FROM jobs WHERE status = 'running' AND lease_expires_ms < ?1");
  s.bind(1, now);
  std::vector<Claim> claims;
  while (s.step())
    if (auto id = JobId::parse(s.text(0)))
      claims.push_back({*id, s.optional_text(1).value_or(""), static_cast<int>(s.int64(2))});
  return claims;
}

Rescued SqliteStore::requeue_expired(Millis now, int max_attempts) {
  std::lock_guard write(impl_->write_mutex);
  auto c = impl_->borrow();
  Transaction tx(*c);
  const std::string expired = " WHERE status = 'running' AND lease_expires_ms < ?1";
  Rescued rescued;
  Statement(*c, "UPDATE jobs SET status = 'canceled', finished_ms = ?1, lease_expires_ms = NULL" + expired +
                    " AND cancel_requested = 1")
      .bind(1, now)
      .run();
  rescued.canceled = c->changes();
  Statement(
      *c,
      "UPDATE jobs SET status = 'failed', finished_ms = ?1, lease_expires_ms = NULL, progress_eta = NULL,"
      " error = 'the worker stopped renewing its lease (process killed or hung) on attempt ' || attempt ||"
      " ' of ' || ?2 || '; not retried'" +
          expired + " AND attempt >= ?2")
      .bind(1, now)
      .bind(2, max_attempts)
      .run();
  rescued.failed = c->changes();
  Statement(*c,
            "UPDATE jobs SET status = 'queued', worker = NULL, lease_expires_ms = NULL, progress_step = 0,"
            " progress_time = 0, progress_eta = NULL" +
                expired)
      .bind(1, now)
      .run();
  rescued.requeued = c->changes();
  tx.commit();
  return rescued;
}

RemoveOutcome SqliteStore::remove(const JobId& id) {
  std::lock_guard write(impl_->write_mutex);
  auto c = impl_->borrow();
  Transaction tx(*c);
  auto job = select_job(*c, id);
  if (!job) return RemoveOutcome::not_found;
  if (!is_terminal(job->status)) return RemoveOutcome::not_finished;
  Statement(*c, "DELETE FROM jobs WHERE id = ?1").bind(1, id.str()).run();
  tx.commit();
  return RemoveOutcome::removed;
}

std::map<Status, std::int64_t> SqliteStore::count_by_status() {
  std::map<Status, std::int64_t> counts;
  for (Status s : all_statuses) counts[s] = 0;
  auto c = impl_->borrow();
  Statement s(*c, "SELECT status, count(*) FROM jobs GROUP BY status");
  while (s.step()) counts[status_column(s, 0)] = s.int64(1);
  return counts;
}

}  // namespace stoss::server::jobs
