#pragma once
/// @file Thin RAII wrappers over libpq (the PostgreSQL C client), for the job store only.

#include <libpq-fe.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "server/jobs/store/store.hpp"

namespace stoss::server::jobs::pg {

/// A statement failed for a reason other than the connection (constraint, syntax, schema).
class Error : public StoreError {
 public:
  using StoreError::StoreError;
};

/// A text parameter of a statement; nullopt is SQL NULL.
using Param = std::optional<std::string>;

/// Formats a double so that it reads back to the same value.
std::string number(double v);

/// The `postgresql://USER:PASSWORD@HOST:PORT/DB` URL with the password replaced by `***`.
std::string redacted(const std::string& url);

/// The rows of one statement. Columns are 0-based.
class Result {
 public:
  explicit Result(PGresult* r) : result_(r) {}
  ~Result() { PQclear(result_); }
  Result(Result&& other) noexcept : result_(other.result_) { other.result_ = nullptr; }
  Result(const Result&) = delete;
  Result& operator=(const Result&) = delete;

  int rows() const { return PQntuples(result_); }
  /// Rows changed by an INSERT/UPDATE/DELETE.
  int changed() const;
  bool is_null(int row, int col) const { return PQgetisnull(result_, row, col) != 0; }
  std::string text(int row, int col) const { return PQgetvalue(result_, row, col); }
  std::int64_t int64(int row, int col) const;
  double real(int row, int col) const;
  bool boolean(int row, int col) const { return text(row, col) == "t"; }
  std::optional<std::string> optional_text(int row, int col) const;
  std::optional<std::int64_t> optional_int64(int row, int col) const;
  std::optional<double> optional_real(int row, int col) const;

 private:
  PGresult* result_;
};

/// One open connection. Throws StoreUnavailable when the server cannot be reached (or refuses the
/// credentials) and pg::Error when a statement fails on a healthy connection.
class Connection {
 public:
  /// Connects to `url` (a libpq URI or key=value string; PG* environment variables fill what it leaves
  /// out) with a 5 s connect timeout unless the URL sets one.
  explicit Connection(const std::string& url);
  ~Connection();
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  /// Runs `sql` with `$1`, `$2`, ... bound to `params` (as text).
  Result exec(const std::string& sql, const std::vector<Param>& params = {});
  /// False once the connection is lost.
  bool ok() const { return PQstatus(conn_) == CONNECTION_OK; }
  PGconn* handle() const { return conn_; }

 private:
  PGconn* conn_ = nullptr;
};

/// BEGIN on construction, ROLLBACK on destruction unless committed.
class Transaction {
 public:
  explicit Transaction(Connection& c);
  ~Transaction();
  void commit();

 private:
  Connection& connection_;
  bool open_ = true;
};

/// Throws a UsageError-like StoreError when `url` is not a PostgreSQL URL libpq can parse; the message
/// names the rule broken.
void check_url(const std::string& url);

}  // namespace stoss::server::jobs::pg
