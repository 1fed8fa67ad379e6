#include "server/jobs/store/pg_store.hpp"

#include <poll.h>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

#include "server/jobs/store/pg.hpp"

namespace stoss::server::jobs {

namespace {

using pg::Connection;
using pg::Param;
using pg::Result;
using pg::Transaction;

/// Schema migrations, in order; migration i brings the database to version i + 1. Never edit one that
/// has shipped: append a new one. (Version 1 is the SQLite store's schema at its version 4.)
const std::vector<std::string> migrations = {
    // 1: the jobs table, with the partial indexes a claim and the rescuer use.
    R"sql(
    CREATE TABLE stoss_jobs (
      seq              BIGSERIAL PRIMARY KEY,
      id               TEXT    NOT NULL UNIQUE CHECK (length(id) = 32),
      kind             TEXT    NOT NULL DEFAULT 'simulation' CHECK (kind IN ('simulation', 'study')),
      status           TEXT    NOT NULL
                       CHECK (status IN ('queued', 'running', 'succeeded', 'failed', 'canceled')),
      created_ms       BIGINT  NOT NULL,
      started_ms       BIGINT,
      finished_ms      BIGINT,
      attempt          INTEGER NOT NULL DEFAULT 0,
      worker           TEXT,
      lease_expires_ms BIGINT,
      cancel_requested BOOLEAN NOT NULL DEFAULT false,
      idempotency_key  TEXT UNIQUE,
      body_hash        TEXT    NOT NULL,
      scene            TEXT    NOT NULL,
      name             TEXT,
      study            TEXT,
      effects          TEXT    NOT NULL,
      progress_step    INTEGER NOT NULL DEFAULT 0,
      progress_steps   INTEGER NOT NULL DEFAULT 0,
      progress_time    DOUBLE PRECISION NOT NULL DEFAULT 0,
      progress_end     DOUBLE PRECISION NOT NULL DEFAULT 0,
      progress_eta     DOUBLE PRECISION,
      summary          TEXT,
      error            TEXT
    );
    CREATE INDEX stoss_jobs_by_status ON stoss_jobs (status, seq);
    CREATE INDEX stoss_jobs_queued ON stoss_jobs (seq) WHERE status = 'queued';
    CREATE INDEX stoss_jobs_by_lease ON stoss_jobs (lease_expires_ms) WHERE status = 'running';
    )sql",
    // 2: each attempt writes in a folder of its own; a finished job names the one it published.
    R"sql(
    ALTER TABLE stoss_jobs ADD COLUMN result_attempt INTEGER;
    )sql",
    // 3: the MPI ranks a job asks for (its scene's solver.ranks); a claim takes only jobs within the
    // worker's --ranks-per-job. Every job that existed before asks for one.
    R"sql(
    ALTER TABLE stoss_jobs ADD COLUMN ranks INTEGER NOT NULL DEFAULT 1 CHECK (ranks >= 1);
    )sql",
};

/// Advisory lock keys (pg_advisory_xact_lock): one migration at a time; one submission at a time, so that
/// the queue limit and idempotency keys hold across processes.
constexpr const char* migration_lock = "SELECT pg_advisory_xact_lock(7461636800001)";
constexpr const char* create_lock = "SELECT pg_advisory_xact_lock(7461636800002)";

/// Every column but `scene` (scenes can be megabytes; only a worker needs one).
const std::string job_columns =
    "seq, id, status, created_ms, started_ms, finished_ms, attempt, worker, lease_expires_ms, "
    "cancel_requested, idempotency_key, body_hash, effects, progress_step, progress_steps, progress_time, "
    "progress_end, progress_eta, summary, error, kind, study, name, result_attempt, ranks";

Param text(const std::string& s) {
  return s;
}
Param integer(std::int64_t v) {
  return std::to_string(v);
}
Param optional_json(const std::optional<nlohmann::json>& j) {
  return j ? Param(j->dump()) : std::nullopt;
}

std::optional<nlohmann::json> json_column(const Result& r, int row, int col) {
  auto t = r.optional_text(row, col);
  if (!t) return std::nullopt;
  return nlohmann::json::parse(*t);
}

/// Reads row `row` selected with `job_columns` (plus `scene` as the next column when `with_scene`).
Job read_job(const Result& r, int row, bool with_scene = false) {
  Job job;
  job.seq = r.int64(row, 0);
  auto id = JobId::parse(r.text(row, 1));
  if (!id) throw pg::Error("job store: malformed id '" + r.text(row, 1) + "'");
  job.id = *id;
  auto status = parse_status(r.text(row, 2));
  if (!status) throw pg::Error("job store: unknown status '" + r.text(row, 2) + "'");
  job.status = *status;
  job.created = r.int64(row, 3);
  job.started = r.optional_int64(row, 4);
  job.finished = r.optional_int64(row, 5);
  job.attempt = static_cast<int>(r.int64(row, 6));
  job.worker = r.optional_text(row, 7);
  job.lease_expires = r.optional_int64(row, 8);
  job.cancel_requested = r.boolean(row, 9);
  job.idempotency_key = r.optional_text(row, 10);
  job.body_hash = r.text(row, 11);
  job.effects = nlohmann::json::parse(r.text(row, 12)).get<std::vector<std::string>>();
  job.progress = {static_cast<int>(r.int64(row, 13)), static_cast<int>(r.int64(row, 14)), r.real(row, 15),
                  r.real(row, 16), r.optional_real(row, 17)};
  job.summary = json_column(r, row, 18);
  job.error = r.optional_text(row, 19);
  auto kind = parse_kind(r.text(row, 20));
  if (!kind) throw pg::Error("job store: unknown kind '" + r.text(row, 20) + "'");
  job.kind = *kind;
  job.study = json_column(r, row, 21);
  job.name = r.optional_text(row, 22);
  if (auto attempt = r.optional_int64(row, 23)) job.result_attempt = static_cast<int>(*attempt);
  job.ranks = static_cast<int>(r.int64(row, 24));
  if (with_scene) job.scene = nlohmann::json::parse(r.text(row, 25));
  return job;
}

/// The WHERE clause of a call naming a claim, its parameters $1 (id), $2 (worker) and $3 (attempt).
const std::string held_by_claim =
    " WHERE id = $1 AND worker = $2 AND attempt = $3::int AND status = 'running'";

/// The parameters of held_by_claim, then `more` as $4, $5, ...
std::vector<Param> claim_params(const Claim& claim, std::vector<Param> more = {}) {
  std::vector<Param> params = {claim.id.str(), claim.worker, integer(claim.attempt)};
  params.insert(params.end(), std::make_move_iterator(more.begin()), std::make_move_iterator(more.end()));
  return params;
}

std::optional<Job> select_job(Connection& c, const JobId& id, const std::string& lock = "") {
  Result r = c.exec("SELECT " + job_columns + " FROM stoss_jobs WHERE id = $1" + lock, {id.str()});
  if (r.rows() == 0) return std::nullopt;
  return read_job(r, 0);
}

int current_version(Connection& c) {
  return static_cast<int>(c.exec("SELECT coalesce(max(version), 0) FROM stoss_schema_version").int64(0, 0));
}

/// Brings the database to the latest schema in one transaction (concurrent starts wait for each other).
void migrate(Connection& c, Millis now) {
  Transaction tx(c);
  c.exec(migration_lock);
  c.exec(
      "CREATE TABLE IF NOT EXISTS stoss_schema_version (version INTEGER PRIMARY KEY, applied_ms BIGINT NOT "
      "NULL)");
  const int version = current_version(c);
  const int latest = static_cast<int>(migrations.size());
  if (version > latest)
    throw StoreError("job store: database schema version " + std::to_string(version) +
                     " is newer than this program's (" + std::to_string(latest) + "); run a newer stoss");
  for (int v = version + 1; v <= latest; ++v) {
    c.exec(migrations[v - 1]);
    c.exec("INSERT INTO stoss_schema_version (version, applied_ms) VALUES ($1, $2)",
           {integer(v), integer(now)});
  }
  tx.commit();
}

std::optional<std::string> scene_name(const nlohmann::json& scene) {
  if (scene.is_object() && scene.contains("name") && scene["name"].is_string())
    return scene["name"].get<std::string>();
  return std::nullopt;
}

/// The LISTEN side: a thread with a connection of its own that passes each notification on, and calls
/// `queued` once more after reconnecting (notifications sent while it was away are lost).
class Listener : public Subscription {
 public:
  Listener(std::string url, StoreEvents events) : url_(std::move(url)), events_(std::move(events)) {
    thread_ = std::thread([this] { loop(); });
  }
  ~Listener() override {
    stopping_ = true;
    thread_.join();
  }

 private:
  void loop() {
    bool lost = false;
    while (!stopping_) {
      try {
        Connection c(url_);
        c.exec(std::string("LISTEN ") + PgStore::channel + "; LISTEN " + PgStore::cancel_channel);
        if (lost && events_.queued) events_.queued();
        lost = false;
        listen(c);
      } catch (const StoreError&) {
      }
      lost = true;
      for (int i = 0; i < 10 && !stopping_; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }

  /// Waits for notifications until the connection breaks or the listener stops.
  void listen(Connection& c) {
    pollfd fd{PQsocket(c.handle()), POLLIN, 0};
    while (!stopping_) {
      if (poll(&fd, 1, 100) < 0) continue;
      if (!(fd.revents & POLLIN)) continue;
      if (!PQconsumeInput(c.handle()) || !c.ok()) return;
      bool queued = false;
      while (PGnotify* n = PQnotifies(c.handle())) {
        if (std::string(n->relname) == PgStore::cancel_channel) {
          const auto id = JobId::parse(n->extra);
          if (id && events_.cancel_requested) events_.cancel_requested(*id);
        } else {
          queued = true;
        }
        PQfreemem(n);
      }
      if (queued && events_.queued) events_.queued();
    }
  }

  std::string url_;
  StoreEvents events_;
  std::atomic<bool> stopping_{false};
  std::thread thread_;
};

}  // namespace

struct PgStore::Impl {
  std::string url;
  const Clock& clock;
  int max_connections;
  std::mutex mutex;
  std::condition_variable freed;
  int borrowed = 0;
  std::vector<std::unique_ptr<Connection>> idle;

  /// A pooled connection, back in the pool when the borrower goes out of scope (dropped if it broke;
  /// then every idle one is dropped too, as a server restart broke them all).
  struct Borrowed {
    Impl& impl;
    std::unique_ptr<Connection> connection;
    ~Borrowed() {
      std::lock_guard lock(impl.mutex);
      --impl.borrowed;
      if (connection->ok())
        impl.idle.push_back(std::move(connection));
      else
        impl.idle.clear();
      impl.freed.notify_one();
    }
    Connection& operator*() { return *connection; }
    Connection* operator->() { return connection.get(); }
  };

  Borrowed borrow() {
    std::unique_ptr<Connection> c;
    {
      std::unique_lock lock(mutex);
      freed.wait(lock, [this] { return borrowed < max_connections; });
      ++borrowed;
      if (!idle.empty()) {
        c = std::move(idle.back());
        idle.pop_back();
      }
    }
    if (!c) {
      try {
        c = std::make_unique<Connection>(url);
      } catch (...) {
        std::lock_guard lock(mutex);
        --borrowed;
        freed.notify_one();
        throw;
      }
    }
    return Borrowed{*this, std::move(c)};
  }
};

PgStore::PgStore(const std::string& url, const Clock& clock, int max_connections)
    : impl_(new Impl{url, clock, max_connections, {}, {}, 0, {}}) {
  pg::check_url(url);
  auto c = impl_->borrow();
  migrate(*c, clock.now());
}

PgStore::~PgStore() = default;

int PgStore::latest_schema_version() {
  return static_cast<int>(migrations.size());
}

int PgStore::schema_version() {
  auto c = impl_->borrow();
  return current_version(*c);
}

CreateResult PgStore::create(const NewJob& job, int max_queued) {
  auto c = impl_->borrow();
  Transaction tx(*c);
  c->exec(create_lock);
  if (job.idempotency_key) {
    Result r = c->exec("SELECT " + job_columns + " FROM stoss_jobs WHERE idempotency_key = $1",
                       {job.idempotency_key});
    if (r.rows() > 0) {
      Job existing = read_job(r, 0);
      const bool same_body = existing.body_hash == job.body_hash;
      return {same_body ? CreateResult::Outcome::existing : CreateResult::Outcome::key_conflict, existing};
    }
  }
  if (c->exec("SELECT count(*) FROM stoss_jobs WHERE status = 'queued'").int64(0, 0) >= max_queued)
    return {CreateResult::Outcome::queue_full, std::nullopt};
  Result r = c->exec(
      "INSERT INTO stoss_jobs (id, status, created_ms, idempotency_key, body_hash, scene, effects,"
      " progress_steps, progress_end, kind, study, name, ranks)"
      " VALUES ($1, 'queued', $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12) RETURNING " +
          job_columns,
      {JobId::random().str(), integer(impl_->clock.now()), job.idempotency_key, job.body_hash,
       job.scene.dump(), nlohmann::json(job.effects).dump(), integer(job.progress.steps),
       pg::number(job.progress.end), to_string(job.kind), optional_json(job.study), scene_name(job.scene),
       integer(scene_ranks(job.scene))});
  Job created = read_job(r, 0);
  c->exec("SELECT pg_notify($1, '')", {text(channel)});  // delivered on commit
  tx.commit();
  return {CreateResult::Outcome::created, created};
}

std::optional<Job> PgStore::get(const JobId& id) {
  auto c = impl_->borrow();
  return select_job(*c, id);
}

std::optional<nlohmann::json> PgStore::scene(const JobId& id) {
  auto c = impl_->borrow();
  Result r = c->exec("SELECT scene FROM stoss_jobs WHERE id = $1", {id.str()});
  if (r.rows() == 0) return std::nullopt;
  return nlohmann::json::parse(r.text(0, 0));
}

Page PgStore::list(std::optional<Status> status, int limit, std::optional<std::int64_t> cursor) {
  auto c = impl_->borrow();
  Result r = c->exec("SELECT " + job_columns +
                         " FROM stoss_jobs WHERE ($1::text IS NULL OR status = $1::text)"
                         " AND ($2::bigint IS NULL OR seq < $2::bigint) ORDER BY seq DESC LIMIT $3",
                     {status ? Param(to_string(*status)) : std::nullopt,
                      cursor ? integer(*cursor) : std::nullopt, integer(limit + 1)});
  Page page;
  for (int row = 0; row < r.rows(); ++row) page.jobs.push_back(read_job(r, row));
  if (static_cast<int>(page.jobs.size()) > limit) {
    page.jobs.pop_back();
    page.next_cursor = page.jobs.back().seq;
  }
  return page;
}

std::optional<Job> PgStore::claim(const std::string& worker, Millis lease, int max_ranks) {
  auto c = impl_->borrow();
  const Millis now = impl_->clock.now();
  // One statement, one short transaction: the subquery locks the oldest queued row within `max_ranks` that
  // no other claim holds (SKIP LOCKED: concurrent claims take different rows instead of waiting for each
  // other).
  Result r = c->exec(
      "UPDATE stoss_jobs SET status = 'running', worker = $1, attempt = attempt + 1, lease_expires_ms = $2,"
      " started_ms = $3, progress_step = 0, progress_time = 0, progress_eta = NULL"
      " WHERE seq = (SELECT seq FROM stoss_jobs WHERE status = 'queued' AND ranks <= $4::int ORDER BY seq"
      " LIMIT 1 FOR UPDATE SKIP LOCKED) AND status = 'queued' RETURNING " +
          job_columns + ", scene",
      {worker, integer(now + lease), integer(now), integer(max_ranks)});
  if (r.rows() == 0) return std::nullopt;
  return read_job(r, 0, true);
}

Lease PgStore::renew(const Claim& claim, Millis lease) {
  auto c = impl_->borrow();
  Result r = c->exec(
      "UPDATE stoss_jobs SET lease_expires_ms = $4::bigint" + held_by_claim + " RETURNING cancel_requested",
      claim_params(claim, {integer(impl_->clock.now() + lease)}));
  if (r.rows() == 0) return Lease::lost;
  return r.boolean(0, 0) ? Lease::cancel_requested : Lease::held;
}

bool PgStore::progress(const Claim& claim, const Progress& p) {
  auto c = impl_->borrow();
  return c->exec(
              "UPDATE stoss_jobs SET progress_step = $4::int, progress_steps = $5::int,"
              " progress_time = $6::double precision, progress_end = $7::double precision,"
              " progress_eta = $8::double precision" +
                  held_by_claim,
              claim_params(claim, {integer(p.step), integer(p.steps), pg::number(p.time), pg::number(p.end),
                                   p.eta_seconds ? Param(pg::number(*p.eta_seconds)) : std::nullopt}))
             .changed() == 1;
}

bool PgStore::finish(const Claim& claim, const Outcome& outcome) {
  auto c = impl_->borrow();
  return c->exec(
              "UPDATE stoss_jobs SET status = $4, summary = $5, error = $6, finished_ms = $7::bigint,"
              " lease_expires_ms = NULL, progress_eta = NULL, result_attempt = $8::int" +
                  held_by_claim,
              claim_params(claim, {to_string(outcome.status), optional_json(outcome.summary), outcome.error,
                                   integer(impl_->clock.now()),
                                   integer(outcome.result_attempt.value_or(claim.attempt))}))
             .changed() == 1;
}

bool PgStore::release(const Claim& claim) {
  auto c = impl_->borrow();
  Transaction tx(*c);
  const bool held = c->exec(
                         "UPDATE stoss_jobs SET status = 'queued', worker = NULL, lease_expires_ms = NULL,"
                         " started_ms = NULL, attempt = attempt - 1, progress_step = 0, progress_time = 0,"
                         " progress_eta = NULL" +
                             held_by_claim,
                         claim_params(claim))
                        .changed() == 1;
  if (held) c->exec("SELECT pg_notify($1, '')", {text(channel)});
  tx.commit();
  return held;
}

CancelResult PgStore::request_cancel(const JobId& id) {
  auto c = impl_->borrow();
  Transaction tx(*c);
  auto job = select_job(*c, id, " FOR UPDATE");
  if (!job) return {CancelResult::Outcome::not_found, std::nullopt};
  CancelResult::Outcome outcome = CancelResult::Outcome::already_done;
  if (job->status == Status::queued) {
    c->exec(
        "UPDATE stoss_jobs SET status = 'canceled', cancel_requested = true, finished_ms = $1 WHERE id = $2",
        {integer(impl_->clock.now()), id.str()});
    outcome = CancelResult::Outcome::canceled;
  } else if (job->status == Status::running) {
    c->exec("UPDATE stoss_jobs SET cancel_requested = true WHERE id = $1", {id.str()});
    c->exec("SELECT pg_notify($1, $2)", {text(cancel_channel), id.str()});  // the worker stops it at once
    outcome = CancelResult::Outcome::requested;
  } else if (job->status == Status::canceled) {
    outcome = CancelResult::Outcome::canceled;
  }
  job = select_job(*c, id);
  tx.commit();
  return {outcome, job};
}

std::vector<Claim> PgStore::expired(Millis now) {
  auto c = impl_->borrow();
  Result r = c->exec(
      "SELECT id, coalesce(worker, ''), attempt FROM stoss_jobs WHERE status = 'running'"
      " AND lease_expires_ms < $1::bigint",
      {integer(now)});
  std::vector<Claim> claims;
  for (int row = 0; row < r.rows(); ++row)
    if (auto id = JobId::parse(r.text(row, 0)))
      claims.push_back({*id, r.text(row, 1), static_cast<int>(r.int64(row, 2))});
  return claims;
}

Rescued PgStore::requeue_expired(Millis now, int max_attempts) {
  auto c = impl_->borrow();
  Transaction tx(*c);
  const std::string expired = " WHERE status = 'running' AND lease_expires_ms < $1::bigint";
  Rescued rescued;
  rescued.canceled = c->exec(
                          "UPDATE stoss_jobs SET status = 'canceled', finished_ms = $1::bigint,"
                          " lease_expires_ms = NULL" +
                              expired + " AND cancel_requested",
                          {integer(now)})
                         .changed();
  rescued.failed =
      c->exec(
           "UPDATE stoss_jobs SET status = 'failed', finished_ms = $1::bigint, lease_expires_ms = NULL,"
           " progress_eta = NULL, error = 'the worker stopped renewing its lease (process killed or hung) on"
           " attempt ' || attempt || ' of ' || $2::int || '; not retried'" +
               expired + " AND attempt >= $2::int",
           {integer(now), integer(max_attempts)})
          .changed();
  rescued.requeued = c->exec(
                          "UPDATE stoss_jobs SET status = 'queued', worker = NULL, lease_expires_ms = NULL,"
                          " progress_step = 0, progress_time = 0, progress_eta = NULL" +
                              expired,
                          {integer(now)})
                         .changed();
  if (rescued.requeued > 0) c->exec("SELECT pg_notify($1, '')", {text(channel)});
  tx.commit();
  return rescued;
}

RemoveOutcome PgStore::remove(const JobId& id) {
  auto c = impl_->borrow();
  Transaction tx(*c);
  auto job = select_job(*c, id, " FOR UPDATE");
  if (!job) return RemoveOutcome::not_found;
  if (!is_terminal(job->status)) return RemoveOutcome::not_finished;
  c->exec("DELETE FROM stoss_jobs WHERE id = $1", {id.str()});
  tx.commit();
  return RemoveOutcome::removed;
}

std::map<Status, std::int64_t> PgStore::count_by_status() {
  std::map<Status, std::int64_t> counts;
  for (Status s : all_statuses) counts[s] = 0;
  auto c = impl_->borrow();
  Result r = c->exec("SELECT status, count(*) FROM stoss_jobs GROUP BY status");
  for (int row = 0; row < r.rows(); ++row) {
    auto status = parse_status(r.text(row, 0));
    if (status) counts[*status] = r.int64(row, 1);
  }
  return counts;
}

std::unique_ptr<Subscription> PgStore::subscribe(StoreEvents events) {
  return std::make_unique<Listener>(impl_->url, std::move(events));
}

}  // namespace stoss::server::jobs
