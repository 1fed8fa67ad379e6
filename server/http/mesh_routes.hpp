#pragma once
/// @file The routes of stored meshes: post, get and delete a mesh file (server/meshes).

#include "server/http/httplib.hpp"
#include "server/http/routes.hpp"

namespace stoss::server::http {

/// POST /v1/meshes: the raw bytes of a .msh or .inp file, parsed once under the limits of --max-nodes (no
/// *INCLUDE), stored by content (201; 200 when the same bytes were stored before); 413 above
/// --max-mesh-store-bytes.
void post_mesh(App& app, const httplib::Request& req, httplib::Response& res);

/// GET /v1/meshes/{id}: the stored file, byte for byte.
void get_mesh(App& app, const httplib::Request& req, httplib::Response& res);

/// DELETE /v1/meshes/{id}: 204, or 409 while a queued or running job names the mesh.
void delete_mesh(App& app, const httplib::Request& req, httplib::Response& res);

}  // namespace stoss::server::http
