#pragma once
/// @file The request gate: what every request passes before and around its route. The token check and the
/// counting body reader around each handler (guarded, reading), the refusals made from the head alone before
/// a body is read (install_request_defaults) and the error and exception handlers that answer problem+json
/// (install_error_handling). The routes themselves are in routes.hpp.

#include "server/http/connection_limit.hpp"
#include "server/http/httplib.hpp"
#include "server/http/limits.hpp"
#include "server/http/metrics.hpp"
#include "server/http/routes.hpp"

namespace stoss::server::http {

/// A route's handler: it answers `req` in `res`, or throws ProblemError.
using RouteHandler = void (*)(App&, const httplib::Request&, httplib::Response&);

/// Checks the token, runs `route`, writes a thrown Problem.
httplib::Server::Handler guarded(App& app, RouteHandler route, bool needs_token);

/// A route that takes a body: cpp-httplib hands it a content reader instead of a body read whole, so the
/// body is counted as it arrives and cut off at max_body_bytes or --request-timeout
/// (read_body_within_limits); the token is checked before a byte of it is read. A body left unread ends
/// the connection once the answer is written (its rest must not be parsed as the next request).
httplib::Server::HandlerWithContentReader reading(App& app, RouteHandler route, bool needs_token);

/// Request hygiene before routing: a POST or DELETE without Content-Length and without Transfer-Encoding
/// has an empty body (RFC 9112 §6.3), as `curl -X POST …/cancel` sends it; cpp-httplib 0.11 would
/// otherwise wait for the client to close the connection. The declared Content-Type moves to
/// declared_type_header (cpp-httplib would parse and cap form bodies); a known path with a method it does
/// not have is answered 405 with Allow. With a `limit`, a connection over the per-client cap is answered
/// 503 before anything else (connection_limit.hpp; /healthz excepted).
///
/// Limits before reading: cpp-httplib 0.11 reads a body after this hook and before the handler, whole
/// into memory and with no cap for a chunked one. So this hook refuses, from the head alone, what must
/// not be read: an unknown route, a missing token (401), a Content-Length above max_body_bytes (413 with
/// the exact length), a chunked body on a route without a counting reader (411) and any other transfer
/// coding (501); such a connection is closed after the answer. The routes that take a body get a content
/// reader instead (reading), which counts the bytes as they arrive and stops at max_body_bytes (413) or
/// --request-timeout after the head (408). A request with `Expect: 100-continue` gets the same refusals
/// instead of the 100.
void install_request_defaults(httplib::Server& server, const App& app, ConnectionLimit* limit = nullptr);

/// The error handler (problem+json for statuses httplib sets itself: unknown route, oversize body, …),
/// the exception handler (catches everything, answers 500, never lets a request take the server down),
/// and the request counter of /metrics.
void install_error_handling(httplib::Server& server, Metrics& metrics, const Limits& limits = {});

}  // namespace stoss::server::http
