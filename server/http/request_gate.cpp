#include "server/http/request_gate.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <iostream>
#include <optional>

#include "server/http/problem.hpp"
#include "server/http/scene_check.hpp"

namespace stoss::server::http {

namespace {

using httplib::Request;
using httplib::Response;

/// When the head of this thread's current request was read (set before routing): --request-timeout
/// counts from here.
thread_local std::optional<std::chrono::steady_clock::time_point> head_read_at;

bool unauthorized(const App& app, const Request& req, bool needs_token) {
  return needs_token && app.auth && !app.auth->allows(req);
}

Problem unauthorized_problem() {
  return {401, "urn:stoss:problem:unauthorized", "Unauthorized",
          "this server needs Authorization: Bearer <token>"};
}

/// The Content-Length of a request: nullopt when absent, not a decimal number or beyond 64 bits.
std::optional<std::uint64_t> content_length(const Request& req) {
  if (!req.has_header("Content-Length")) return std::nullopt;
  const std::string text = req.get_header_value("Content-Length");
  std::uint64_t value = 0;
  if (text.empty() || text.size() > 20) return std::nullopt;
  for (char c : text)
    if (c < '0' || c > '9' || __builtin_mul_overflow(value, 10u, &value) ||
        __builtin_add_overflow(value, static_cast<unsigned>(c - '0'), &value))
      return std::nullopt;
  return value;
}

bool is_health_check(const Request& req) {
  return req.path == "/healthz" && (req.method == "GET" || req.method == "HEAD");
}

/// The answer to a request that must not have its body read: no route for it, no token, a transfer
/// coding other than chunked (RFC 9112 §6.1: 501), a chunked body on a route that reads none through the
/// counting reader (411: send a Content-Length), a Content-Length that is not a number (400) or above
/// max_body_bytes (413, the exact length as `value`). nullopt: route it.
std::optional<Problem> refuse_before_reading(const App& app, const Request& req, bool body_announced) {
  const RouteInfo* route = find_route(req);
  if (!route) {
    if (!body_announced) return std::nullopt;  // answered 404 by the error handler
    return problem_for_status(404, req);
  }
  if (unauthorized(app, req, route->needs_token)) return unauthorized_problem();
  if (req.has_header("Transfer-Encoding")) {
    std::string coding = req.get_header_value("Transfer-Encoding");
    std::transform(coding.begin(), coding.end(), coding.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (coding != "chunked")
      return Problem{501, "urn:stoss:problem:unsupported-transfer-coding", "Not Implemented",
                     "Transfer-Encoding '" + coding.substr(0, 100) +
                         "' is not supported; send chunked or a Content-Length"};
    if (route->method != "POST")
      return Problem{
          411, "urn:stoss:problem:length-required", "Length Required",
          req.method + " " + req.path.substr(0, 200) + " takes no chunked body; send a Content-Length"};
  }
  if (req.has_header("Content-Length")) {
    const auto length = content_length(req);
    if (!length)
      return Problem{400, "urn:stoss:problem:bad-content-length", "Bad Request",
                     "Content-Length must be a decimal number of bytes below 2^64"};
    if (*length > app.limits.max_body_bytes) return body_too_large(app.limits.max_body_bytes, length);
  }
  return std::nullopt;
}

/// Request hygiene (install_request_defaults): an unframed body is empty, the Content-Type moves aside,
/// ranges are left to the handlers.
void normalize_request(Request& request) {
  const bool framed = request.has_header("Content-Length") || request.has_header("Transfer-Encoding");
  if (!framed) request.set_header("Content-Length", "0");
  // The client's Content-Type moves aside: cpp-httplib would parse a form body (and cap it at 8 KiB,
  // CPPHTTPLIB_FORM_URL_ENCODED_PAYLOAD_MAX_LENGTH, compiled into the library) or a multipart body
  // before any handler ran. Handlers read the declared type from declared_type_header.
  request.headers.erase(declared_type_header);
  if (request.has_header("Content-Type")) {
    request.headers.emplace(declared_type_header, request.get_header_value("Content-Type"));
    request.headers.erase("Content-Type");
  }
  // Ranges are applied by the handlers that honour them (RFC 9110 §14), not by cpp-httplib.
  request.ranges.clear();
}

/// A path the API has, with a method it has not: 405 with Allow.
std::optional<Problem> method_not_allowed(const Request& req, Response& res) {
  const std::vector<std::string> allowed = allowed_methods(req.path);
  const bool head_of_get =
      req.method == "HEAD" && std::find(allowed.begin(), allowed.end(), "GET") != allowed.end();
  if (allowed.empty() || head_of_get ||
      std::find(allowed.begin(), allowed.end(), req.method) != allowed.end())
    return std::nullopt;
  std::string allow;
  for (const auto& m : allowed) allow += (allow.empty() ? "" : ", ") + m;
  res.set_header("Allow", allow);
  return Problem{405, "urn:stoss:problem:method-not-allowed", "Method Not Allowed",
                 req.method + " is not allowed on " + req.path + "; allowed: " + allow};
}

}  // namespace

/// Checks the token, runs the route, writes a thrown Problem.
httplib::Server::Handler guarded(App& app, RouteHandler route, bool needs_token) {
  return [&app, route, needs_token](const Request& req, Response& res) {
    try {
      if (unauthorized(app, req, needs_token)) throw ProblemError(unauthorized_problem());
      route(app, req, res);
    } catch (const ProblemError& e) {
      e.problem().write(res);
    }
  };
}

/// A route that takes a body: cpp-httplib hands it a content reader instead of a body read whole, so the
/// body is counted as it arrives and cut off at max_body_bytes or --request-timeout
/// (read_body_within_limits); the token is checked before a byte of it is read. A body left unread ends
/// the connection once the answer is written (its rest must not be parsed as the next request).
httplib::Server::HandlerWithContentReader reading(App& app, RouteHandler route, bool needs_token) {
  return [&app, route, needs_token](const Request& req, Response& res, const httplib::ContentReader& reader) {
    try {
      if (unauthorized(app, req, needs_token)) {
        close_after_answer(req);
        throw ProblemError(unauthorized_problem());
      }
      const auto deadline =
          head_read_at.value_or(std::chrono::steady_clock::now()) + app.limits.request_timeout;
      try {
        const_cast<Request&>(req).body = read_body_within_limits(reader, app.limits, deadline, res);
      } catch (const ProblemError&) {
        close_after_answer(req);
        throw;
      }
      route(app, req, res);
    } catch (const ProblemError& e) {
      e.problem().write(res);
    }
  };
}

void install_request_defaults(httplib::Server& server, const App& app, ConnectionLimit* limit) {
  server.set_pre_routing_handler([&app, limit](const Request& req, Response& res) {
    head_read_at = std::chrono::steady_clock::now();
    if (limit && !limit->admit(req.remote_addr)) {
      if (!is_health_check(req)) {
        refuse_connection(*limit, req, res);
        return httplib::Server::HandlerResponse::Handled;
      }
      close_after_answer(req);  // over the cap, /healthz is answered; then its connection ends
    }
    // `req` is the server's own non-const Request, handed to this hook as const.
    normalize_request(const_cast<Request&>(req));
    // Limits before reading: whatever is refused here, its body has not been read (cpp-httplib reads it
    // after this hook), and the connection ends once the answer is written.
    const bool body_announced =
        req.has_header("Transfer-Encoding") || req.get_header_value("Content-Length") != "0";
    auto refusal = method_not_allowed(req, res);
    if (!refusal) refusal = refuse_before_reading(app, req, body_announced);
    if (!refusal) return httplib::Server::HandlerResponse::Unhandled;
    refusal->write(res);
    if (body_announced) close_after_answer(req);
    return httplib::Server::HandlerResponse::Handled;
  });
  // A client that waits for "100 Continue" before sending its body (curl does above 1 MiB) gets the
  // refusal instead, and sends no body at all.
  server.set_expect_100_continue_handler([&app](const Request& req, Response& res) {
    const auto refusal = refuse_before_reading(app, req, true);
    if (!refusal) return 100;
    refusal->write(res);
    close_after_answer(req);
    return refusal->status;
  });
}

void install_error_handling(httplib::Server& server, Metrics& metrics, const Limits& limits) {
  const std::size_t max_body = limits.max_body_bytes;
  server.set_error_handler(
      httplib::Server::HandlerWithResponse([max_body](const Request& req, Response& res) {
        if (!res.body.empty() || res.has_header("Content-Length"))
          return httplib::Server::HandlerResponse::Unhandled;
        if (res.status == 413) {  // cpp-httplib refused a body above the payload limit, before any handler
          body_too_large(max_body, content_length(req)).write(res);
          return httplib::Server::HandlerResponse::Handled;
        }
        problem_for_status(res.status, req).write(res);
        return httplib::Server::HandlerResponse::Handled;
      }));
  server.set_exception_handler([](const Request& req, Response& res, std::exception_ptr error) {
    std::string what = "unknown exception";
    try {
      std::rethrow_exception(error);
    } catch (const jobs::StoreUnavailable& e) {  // the database is away (restarting): 503, Retry-After
      std::cerr << "stoss: " << req.method << " " << req.path << ": job store unavailable: " << e.what()
                << std::endl;
      return Problem{503, "urn:stoss:problem:store-unavailable", "Job store unavailable",
                     "the job store cannot be reached just now; retry later (a POST retried with the same "
                     "Idempotency-Key is not queued twice)"}
          .write(res);
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
    std::cerr << "stoss: " << req.method << " " << req.path << " failed: " << what << std::endl;
    Problem{500, "urn:stoss:problem:internal", "Internal Server Error", what}.write(res);
  });
  server.set_logger([&metrics](const Request& req, const Response& res) {
    metrics.count_request(res.status);
    end_marked_connection(req);  // a connection over the per-client cap, or with a body left unread, ends
  });
}

}  // namespace stoss::server::http
