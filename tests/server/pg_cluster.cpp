#include "tests/server/pg_cluster.hpp"

#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include "server/jobs/id.hpp"
#include "server/jobs/store/pg.hpp"
#include "server/jobs/store/pg_store.hpp"
#include "server/jobs/store/sqlite_store.hpp"
#include "tests/server/live_server.hpp"

namespace stoss::test {

namespace {

const std::string script = std::string(STOSS_SOURCE_DIR) + "/tests/server/pg_cluster.sh";

/// Runs `command` through the shell; its stdout. Throws when it fails.
std::string shell(const std::string& command) {
  int status = 0;
  const std::string out = shell_output(command, &status);
  if (status != 0) throw std::runtime_error(command + " failed: " + out);
  return out;
}

}  // namespace

PgCluster::PgCluster() {
  std::string pattern = "/tmp/stoss-pg-XXXXXX";  // /tmp: `nobody` must reach it
  if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
  dir_ = pattern;
  port_ = free_port();
  start();
}

PgCluster::~PgCluster() {
  if (!owned_) return;
  try {
    shell(script + " remove " + dir_.string());
  } catch (...) {
  }
}

PgCluster& PgCluster::shared() {
  static const std::unique_ptr<PgCluster> cluster = []() -> std::unique_ptr<PgCluster> {
    const char* dir = std::getenv("STOSS_TEST_PG_CLUSTER");
    if (dir) {
      std::ifstream port_file(std::filesystem::path(dir) / "port");
      int port = 0;
      if (port_file >> port) return std::unique_ptr<PgCluster>(new PgCluster(dir, port));
    }
    return std::make_unique<PgCluster>();
  }();
  return *cluster;
}

std::string PgCluster::url(const std::string& db) const {
  return "postgresql://stoss:secret@127.0.0.1:" + std::to_string(port_) + "/" + db;
}

std::string PgCluster::create_database() {
  const std::string name = "t_" + server::jobs::JobId::random().str().substr(0, 12);
  server::jobs::pg::Connection(url()).exec("CREATE DATABASE " + name);
  return name;
}

void PgCluster::drop_database(const std::string& db) {
  server::jobs::pg::Connection(url()).exec("DROP DATABASE IF EXISTS " + db + " WITH (FORCE)");
}

void PgCluster::stop() {
  shell(script + " stop " + dir_.string());
}

void PgCluster::start() {
  shell(script + " start " + dir_.string() + " " + std::to_string(port_));
}

std::string to_string(Backend b) {
  return b == Backend::sqlite ? "Sqlite" : "Postgresql";
}

StoreUnderTest::StoreUnderTest(Backend backend, const server::jobs::Clock& clock)
    : backend_(backend), clock_(clock) {
  if (backend == Backend::sqlite) {
    std::string pattern = (std::filesystem::temp_directory_path() / "stoss-test-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
    dir_ = pattern;
  } else {
    database_ = PgCluster::shared().create_database();
  }
  store_ = open_again();
}

StoreUnderTest::~StoreUnderTest() {
  store_.reset();
  std::error_code ignored;
  if (!dir_.empty()) std::filesystem::remove_all(dir_, ignored);
  if (!database_.empty()) {
    try {
      PgCluster::shared().drop_database(database_);
    } catch (...) {
    }
  }
}

std::unique_ptr<server::jobs::JobStore> StoreUnderTest::open_again() const {
  if (backend_ == Backend::sqlite)
    return std::make_unique<server::jobs::SqliteStore>(dir_ / "jobs.db", clock_);
  return std::make_unique<server::jobs::PgStore>(PgCluster::shared().url(database_), clock_);
}

LiveWorker::LiveWorker(const std::string& store, const std::filesystem::path& data,
                       std::vector<std::string> extra) {
  static std::atomic<int> counter{0};
  std::filesystem::create_directories(data);
  out_ = data / ("worker-" + std::to_string(counter++) + ".log");
  std::vector<std::string> args = {"worker", "--store", store, "--data", data.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  pid_ = spawn_stoss(args, out_);
  if (!eventually([&] { return read_text(out_).find(" running ") != std::string::npos; },
                  std::chrono::seconds(30))) {
    kill9();
    throw std::runtime_error("stoss worker did not start: " + read_text(out_));
  }
}

LiveWorker::~LiveWorker() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGTERM);
  waitpid(pid_, nullptr, 0);
}

void LiveWorker::kill9() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGKILL);
  waitpid(pid_, nullptr, 0);
  pid_ = -1;
}

}  // namespace stoss::test
