#pragma once
/// @file The routes of the service itself, about no job: the scene check, the scene schema, the OpenAPI
/// document, health and metrics.

#include "server/http/httplib.hpp"
#include "server/http/routes.hpp"

namespace stoss::server::http {

/// POST /v1/validate: the scene's checks without a job: its size, effects, warnings and estimates.
void validate_scene(App& app, const httplib::Request& req, httplib::Response& res);

/// GET /v1/schema/scene: api/scene.schema.json as compiled in.
void get_schema(App&, const httplib::Request&, httplib::Response& res);

/// api/openapi.yaml, as in the source tree this binary was built from.
void get_openapi(App&, const httplib::Request&, httplib::Response& res);

/// GET /healthz: {"status": "ok"}, without the token.
void get_health(App&, const httplib::Request&, httplib::Response& res);

/// GET /metrics: the Prometheus text of metrics.hpp, with jobs by status and running workers.
void get_metrics(App& app, const httplib::Request&, httplib::Response& res);

}  // namespace stoss::server::http
