#include "server/http/mesh_routes.hpp"

#include <filesystem>
#include <string>
#include <vector>

#include "core/mesh/mesh_file.hpp"
#include "server/http/problem.hpp"
#include "server/http/route_support.hpp"
#include "server/http/scene_check.hpp"
#include "server/meshes/mesh_store.hpp"

namespace stoss::server::http {

namespace {

using httplib::Request;
using httplib::Response;

/// The format of a posted mesh: the `format` parameter, else what the bytes look like.
std::string mesh_format(const Request& req) {
  if (req.has_param("format")) return format_param(req, {"msh", "inp"});
  const std::string sniffed = meshes::sniff_mesh_format(req.body);
  if (sniffed.empty())
    fail(400, "bad-parameter", "Bad parameter",
         "cannot tell the mesh format from the body (a Gmsh file starts with $MeshFormat, an Abaqus/CalculiX "
         "deck with a *KEYWORD line); give format=msh or format=inp");
  return sniffed;
}

/// name → size (elements of a set, faces of a surface).
template <typename Map>
nlohmann::json sizes(const Map& named) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, items] : named) out[name] = items.size();
  return out;
}

/// 422 for a mesh file that is not usable, naming the line when there is one.
[[noreturn]] void invalid_mesh(const mesh::MeshFileError& e, const std::string& format) {
  Problem problem{422, "urn:stoss:problem:invalid-mesh", "Invalid mesh", e.what()};
  if (e.line > 0) problem.extra["line"] = e.line;
  problem.extra["format"] = format;
  throw ProblemError(problem);
}

/// The stored file of the mesh id in the path's first capture; 404 when there is none.
std::filesystem::path find_mesh(App& app, const Request& req) {
  const std::string id = req.matches[1].str();
  const auto path = meshes::MeshStore::at(app.files.meshes()).path_of(id);
  if (!path)
    fail(404, "unknown-mesh", "Unknown mesh",
         "no mesh " + id.substr(0, 64) +
             " (mesh ids are 64 lowercase hex digits, as POST /v1/meshes answers)");
  return *path;
}

}  // namespace

void post_mesh(App& app, const Request& req, Response& res) {
  if (req.body.size() > app.limits.max_body_bytes)
    throw ProblemError(body_too_large(app.limits.max_body_bytes, req.body.size()));
  const std::string format = mesh_format(req);
  if (req.body.empty())
    fail(400, "empty-body", "Empty body", "the body is empty; send the bytes of a .msh or .inp file");
  meshes::StoredMesh stored;
  try {
    stored = meshes::MeshStore::at(app.files.meshes())
                 .store(req.body, format, mesh::upload_limits(app.limits.max_nodes),
                        app.limits.max_mesh_store_bytes);
  } catch (const mesh::MeshFileError& e) {
    invalid_mesh(e, format);
  } catch (const meshes::MeshStoreFull& e) {
    throw ProblemError(Problem{413,
                               "urn:stoss:problem:mesh-store-full",
                               "Mesh store full",
                               std::string(e.what()) + "; DELETE /v1/meshes/{id} of meshes no longer needed",
                               {{"limits", nlohmann::json::array({{{"name", "max_mesh_store_bytes"},
                                                                   {"limit", e.limit},
                                                                   {"value", e.used + e.size}}})}}});
  }
  if (stored.created) res.set_header("Location", "/v1/meshes/" + stored.id);
  send_json(res, stored.created ? 201 : 200,
            {{"id", stored.id},
             {"format", stored.format},
             {"nodes", stored.mesh->nodes.size()},
             {"elements", stored.mesh->hex8.size()},
             {"element_sets", sizes(stored.mesh->element_sets)},
             {"surfaces", sizes(stored.mesh->surfaces)}});
}

void get_mesh(App& app, const Request& req, Response& res) {
  const auto path = find_mesh(app, req);
  res.set_header("Content-Disposition", "attachment; filename=\"" + path.filename().string() + "\"");
  res.set_header("Cache-Control", "public, max-age=31536000, immutable");
  stream_file(req, res, path, "application/octet-stream");
}

void delete_mesh(App& app, const Request& req, Response& res) {
  const std::string id = find_mesh(app, req).stem().string();
  const std::vector<jobs::JobId> users = app.store.active_jobs_using_mesh(id);
  if (!users.empty()) {
    nlohmann::json ids = nlohmann::json::array();
    for (const auto& job : users) ids.push_back(job.str());
    throw ProblemError(Problem{409,
                               "urn:stoss:problem:mesh-in-use",
                               "Mesh in use",
                               "mesh " + id + " is named by " + std::to_string(users.size()) +
                                   " queued or running job(s), the first " + users.front().str() +
                                   "; delete it once they ended (or cancel them)",
                               {{"jobs", ids}}});
  }
  if (!meshes::MeshStore::at(app.files.meshes()).remove(id))
    fail(404, "unknown-mesh", "Unknown mesh", "no mesh " + id);
  res.status = 204;
}

}  // namespace stoss::server::http
