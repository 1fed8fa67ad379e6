#pragma once
/// @file The routes that serve a job's files: the HDF5 result and its XDMF sidecars, the series (whole or
/// partial while it runs), a study's table, the log.

#include "server/http/httplib.hpp"
#include "server/http/routes.hpp"

namespace stoss::server::http {

/// GET /v1/jobs/{id}/result: result.h5 with an ETag (304 on If-None-Match) and byte ranges.
void get_result(App& app, const httplib::Request& req, httplib::Response& res);

/// GET /v1/jobs/{id}/result.xdmf: the sidecar of the frames.
void get_result_xdmf(App& app, const httplib::Request& req, httplib::Response& res);

/// GET /v1/jobs/{id}/result_mesh.xdmf: the sidecar of the mesh.
void get_result_mesh_xdmf(App& app, const httplib::Request& req, httplib::Response& res);

/// GET /v1/jobs/{id}/series: JSON or CSV, after ?since; partial (Stoss-Completed: false) before the job
/// succeeded.
void get_series(App& app, const httplib::Request& req, httplib::Response& res);

/// A study job's table: JSON as written (study::to_json), CSV or Markdown made from it.
void get_study(App& app, const httplib::Request& req, httplib::Response& res);

/// GET /v1/jobs/{id}/log: the job's log as text.
void get_log(App& app, const httplib::Request& req, httplib::Response& res);

}  // namespace stoss::server::http
