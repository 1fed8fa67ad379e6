#pragma once
/// @file The routes of a job itself: submit a scene or a study, list, get, cancel, delete, and the scene it
/// ran.

#include "server/http/httplib.hpp"
#include "server/http/routes.hpp"

namespace stoss::server::http {

/// POST /v1/jobs: the scene checked, resolved and queued as a job (201; 200 for a repeated Idempotency-Key).
void submit_job(App& app, const httplib::Request& req, httplib::Response& res);

/// POST /v1/studies: a study is a job of kind "study": progress counts runs; its table is served by
/// get_study.
void submit_study(App& app, const httplib::Request& req, httplib::Response& res);

/// GET /v1/jobs: ?verdict filters the store's page (the stores keep no verdict column): a page may hold fewer
/// than `limit` jobs, and next_cursor goes on where the store's page ended.
void list_jobs(App& app, const httplib::Request& req, httplib::Response& res);

/// GET /v1/jobs/{id}: the job JSON.
void get_job(App& app, const httplib::Request& req, httplib::Response& res);

/// POST /v1/jobs/{id}/cancel: 202 with the job JSON; 409 once the job ended.
void cancel_job(App& app, const httplib::Request& req, httplib::Response& res);

/// DELETE /v1/jobs/{id}: the job and its files (204); 409 while it is not finished.
void delete_job(App& app, const httplib::Request& req, httplib::Response& res);

/// The scene of a job as it was posted (for a study: the study's scene); `?resolved=true` with every
/// default of the schema filled in.
void get_scene(App& app, const httplib::Request& req, httplib::Response& res);

}  // namespace stoss::server::http
