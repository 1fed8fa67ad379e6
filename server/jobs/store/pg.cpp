#include "server/jobs/store/pg.hpp"

#include <cstdio>
#include <cstdlib>
#include <regex>

namespace stoss::server::jobs::pg {

namespace {

/// libpq's message on one line: no trailing newline, inner line breaks and tabs as "; " and " ".
std::string trimmed(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  std::string line;
  for (char c : text) {
    if (c == '\n')
      line += "; ";
    else if (c != '\t')
      line += c;
  }
  return line;
}

/// SQLSTATE classes and codes that mean "the server is away", not "the statement is wrong": connection
/// exceptions (08), shutting down or starting up (57P01-57P03), too many connections (53300).
bool is_unavailable(const char* sqlstate) {
  if (!sqlstate) return true;  // no server answer at all
  const std::string code = sqlstate;
  return code.rfind("08", 0) == 0 || code == "57P01" || code == "57P02" || code == "57P03" || code == "53300";
}

}  // namespace

std::string number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

std::string redacted(const std::string& url) {
  static const std::regex password(R"(^(postgres(?:ql)?://[^:@/]*:)[^@/]*@)");
  return std::regex_replace(url, password, "$1***@");
}

int Result::changed() const {
  const char* n = PQcmdTuples(result_);
  return n && *n ? std::atoi(n) : 0;
}

std::int64_t Result::int64(int row, int col) const {
  return std::strtoll(PQgetvalue(result_, row, col), nullptr, 10);
}

double Result::real(int row, int col) const {
  return std::strtod(PQgetvalue(result_, row, col), nullptr);
}

std::optional<std::string> Result::optional_text(int row, int col) const {
  if (is_null(row, col)) return std::nullopt;
  return text(row, col);
}

std::optional<std::int64_t> Result::optional_int64(int row, int col) const {
  if (is_null(row, col)) return std::nullopt;
  return int64(row, col);
}

std::optional<double> Result::optional_real(int row, int col) const {
  if (is_null(row, col)) return std::nullopt;
  return real(row, col);
}

Connection::Connection(const std::string& url) {
  // connect_timeout first: an expanded dbname (the URL) overrides it when it sets its own.
  const char* keys[] = {"connect_timeout", "application_name", "dbname", nullptr};
  const char* values[] = {"5", "stoss", url.c_str(), nullptr};
  conn_ = PQconnectdbParams(keys, values, 1);
  if (!conn_) throw StoreUnavailable("postgresql: out of memory connecting to " + redacted(url));
  if (PQstatus(conn_) != CONNECTION_OK) {
    const std::string message = trimmed(PQerrorMessage(conn_));
    PQfinish(conn_);
    conn_ = nullptr;
    throw StoreUnavailable("cannot connect: " + message);
  }
  PQsetNoticeProcessor(
      conn_, [](void*, const char*) {}, nullptr);  // "relation already exists, skipping"
}

Connection::~Connection() {
  if (conn_) PQfinish(conn_);
}

Result Connection::exec(const std::string& sql, const std::vector<Param>& params) {
  std::vector<const char*> values;
  values.reserve(params.size());
  for (const Param& p : params) values.push_back(p ? p->c_str() : nullptr);
  // Without parameters, the simple protocol: it also runs several statements at once (migrations).
  PGresult* r = params.empty() ? PQexec(conn_, sql.c_str())
                               : PQexecParams(conn_, sql.c_str(), static_cast<int>(values.size()), nullptr,
                                              values.data(), nullptr, nullptr, 0);
  const ExecStatusType status = r ? PQresultStatus(r) : PGRES_FATAL_ERROR;
  if (status == PGRES_COMMAND_OK || status == PGRES_TUPLES_OK) return Result(r);
  const char* sqlstate = r ? PQresultErrorField(r, PG_DIAG_SQLSTATE) : nullptr;
  const std::string message = trimmed(r ? PQresultErrorMessage(r) : PQerrorMessage(conn_));
  const bool away = !ok() || is_unavailable(sqlstate);
  PQclear(r);
  const std::string what = "postgresql: " + message + " in: " + trimmed(sql.substr(0, 80));
  if (away) throw StoreUnavailable(what);
  throw Error(what);
}

Transaction::Transaction(Connection& c) : connection_(c) {
  c.exec("BEGIN");
}

Transaction::~Transaction() {
  if (!open_ || !connection_.ok()) return;
  try {
    connection_.exec("ROLLBACK");
  } catch (...) {  // the connection went away: the server rolls back on its own
  }
}

void Transaction::commit() {
  connection_.exec("COMMIT");
  open_ = false;
}

void check_url(const std::string& url) {
  if (url.rfind("postgresql://", 0) != 0 && url.rfind("postgres://", 0) != 0)
    throw StoreError("a PostgreSQL store URL starts with postgresql://, got '" + redacted(url) + "'");
  // userinfo@, then a host (an IPv6 literal in brackets, or up to the port's colon), then :PORT.
  static const std::regex port(R"(^postgres(?:ql)?://(?:[^@/]*@)?)"
                               R"((?:\[[^\]/]*\]|[^:/?\[]*):([^/?]*)(?:[/?].*)?$)");
  std::smatch m;
  if (std::regex_match(url, m, port)) {
    const std::string p = m[1];
    const bool digits = !p.empty() && p.size() <= 5 && p.find_first_not_of("0123456789") == std::string::npos;
    if (!digits || std::stoi(p) < 1 || std::stoi(p) > 65535)
      throw StoreError("the port of a PostgreSQL store URL must be an integer in [1, 65535], got '" + p +
                       "'");
  }
  char* error = nullptr;
  PQconninfoOption* options = PQconninfoParse(url.c_str(), &error);
  if (!options) {
    const std::string message = error ? trimmed(error) : "out of memory";
    PQfreemem(error);
    throw StoreError("malformed PostgreSQL store URL '" + redacted(url) + "': " + message);
  }
  PQconninfoFree(options);
}

}  // namespace stoss::server::jobs::pg
