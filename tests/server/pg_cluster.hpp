#pragma once
/// @file Test support: a throwaway PostgreSQL cluster (tests/server/pg_cluster.sh: initdb into a temporary
/// directory, as `nobody` when run as root, on a free loopback port, removed at the end), and a job store
/// of either kind for the store contract tests.

#include <sys/types.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "server/jobs/clock.hpp"
#include "server/jobs/store/store.hpp"

namespace stoss::test {

/// A PostgreSQL cluster of its own, started by the constructor and removed by the destructor.
class PgCluster {
 public:
  PgCluster();
  ~PgCluster();
  PgCluster(const PgCluster&) = delete;
  PgCluster& operator=(const PgCluster&) = delete;

  /// The cluster the contract tests share: the ctest run's (STOSS_TEST_PG_CLUSTER names its directory,
  /// started by the fixture test PgCluster.Start), else one of this process's, started on first use and
  /// removed at exit.
  static PgCluster& shared();

  int port() const { return port_; }
  /// postgresql://stoss:secret@127.0.0.1:PORT/DB (the superuser).
  std::string url(const std::string& db = "postgres") const;
  /// A new empty database; its name.
  std::string create_database();
  /// Drops `db`, ending its connections.
  void drop_database(const std::string& db);
  /// Fast shutdown (every connection ends); start() brings the same data back on the same port.
  void stop();
  void start();

 private:
  /// Uses the running cluster in `dir` on `port` without owning it.
  PgCluster(std::filesystem::path dir, int port) : dir_(std::move(dir)), port_(port), owned_(false) {}

  std::filesystem::path dir_;
  int port_ = 0;
  bool owned_ = true;
};

/// Which JobStore a contract test runs against.
enum class Backend { sqlite, postgresql };
std::string to_string(Backend b);

/// A fresh store of one kind: an SQLite file in a temporary directory, or a new database in the shared
/// cluster (dropped at the end).
class StoreUnderTest {
 public:
  StoreUnderTest(Backend backend, const server::jobs::Clock& clock);
  ~StoreUnderTest();

  server::jobs::JobStore& store() { return *store_; }
  /// Another store object on the same database (as a restarted process, or a second process, opens it).
  std::unique_ptr<server::jobs::JobStore> open_again() const;

 private:
  Backend backend_;
  const server::jobs::Clock& clock_;
  std::filesystem::path dir_;
  std::string database_;
  std::unique_ptr<server::jobs::JobStore> store_;
};

/// `stoss worker --store STORE --data DATA ...` in a child process, up once it printed its name; SIGTERM
/// and wait at the end.
class LiveWorker {
 public:
  LiveWorker(const std::string& store, const std::filesystem::path& data,
             std::vector<std::string> extra = {});
  ~LiveWorker();
  LiveWorker(const LiveWorker&) = delete;
  LiveWorker& operator=(const LiveWorker&) = delete;

  pid_t pid() const { return pid_; }
  /// SIGKILL, as a crash would; the process is reaped.
  void kill9();

 private:
  pid_t pid_ = -1;
  std::filesystem::path out_;
};

}  // namespace stoss::test
