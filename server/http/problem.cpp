#include "server/http/problem.hpp"

namespace stoss::server::http {

std::string dump(const nlohmann::json& j) {
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

nlohmann::json Problem::to_json() const {
  nlohmann::json j = {{"type", type.empty() ? "about:blank" : type}, {"title", title}, {"status", status}};
  if (!detail.empty()) j["detail"] = detail;
  for (auto& [key, value] : extra.items()) j[key] = value;
  return j;
}

void Problem::write(httplib::Response& res) const {
  res.status = status;
  if (status == 401) res.set_header("WWW-Authenticate", "Bearer");
  if (status == 503) res.set_header("Retry-After", "5");
  if (status == 415) res.set_header("Accept-Post", "application/json");
  res.set_content(dump(to_json()), "application/problem+json");
}

Problem problem_for_status(int status, const httplib::Request& req) {
  switch (status) {
    case 404:
      return {404, "urn:stoss:problem:no-route", "Not Found",
              "no route for " + req.method + " " + req.path + " (see api/openapi.yaml)"};
    case 413:
      return {413,
              "urn:stoss:problem:limit-exceeded",
              "Request body too large",
              "the request body exceeds the server limit max_body_bytes",
              {{"limits", {{{"name", "max_body_bytes"}}}}}};
    case 414:
      return {414, "", "URI Too Long", "the request target is too long"};
    case 416:
      return {416, "", "Range Not Satisfiable", "the Range header cannot be satisfied"};
    case 400:
      return {400, "", "Bad Request", "the request could not be read"};
    case 405:
      return {405, "", "Method Not Allowed", req.method + " is not allowed on " + req.path};
    default:
      return {status, "", status >= 500 ? "Server Error" : "Client Error", ""};
  }
}

}  // namespace stoss::server::http
