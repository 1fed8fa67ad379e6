#pragma once
/// @file Problem: an RFC 9457 `application/problem+json` error, the only way the HTTP layer reports one.

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "server/http/httplib.hpp"

namespace stoss::server::http {

/// One error response. `type` is a URN naming the kind of problem (`urn:stoss:problem:<kind>`);
/// `extra` members are merged into the body (e.g. `errors` for scene errors, `limits` for limits).
struct Problem {
  int status = 500;
  std::string type;
  std::string title;
  std::string detail;
  nlohmann::json extra = nlohmann::json::object();

  nlohmann::json to_json() const;
  /// Sets status, Content-Type application/problem+json and the body (plus WWW-Authenticate on 401,
  /// Retry-After on 503).
  void write(httplib::Response& res) const;
};

/// A Problem thrown by a route handler; the route wrapper writes it.
class ProblemError : public std::exception {
 public:
  explicit ProblemError(Problem p) : problem_(std::move(p)) {}
  const Problem& problem() const { return problem_; }
  const char* what() const noexcept override { return problem_.title.c_str(); }

 private:
  Problem problem_;
};

/// The problem for a status code httplib produced itself (unknown route, oversize body, bad request line).
Problem problem_for_status(int status, const httplib::Request& req);

/// `j` as compact JSON text; invalid UTF-8 from user input is replaced, never thrown on.
std::string dump(const nlohmann::json& j);

}  // namespace stoss::server::http
