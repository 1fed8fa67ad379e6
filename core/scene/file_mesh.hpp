#pragma once
/// @file Scene bodies meshed from a file: "mesh": {"file": "part.msh", "elements": "NAME", "transform":
/// {...}}, or {"id": "<sha256>", ...} for a mesh stored by the service (POST /v1/meshes). "file" is resolved
/// relative to the scene file's directory, "id" by the store (Checker::mesh_files, see MeshFiles); a scene
/// posted to the HTTP API names its meshes by id.

#include <filesystem>
#include <optional>
#include <set>
#include <string>

#include "core/mesh/mesh_file.hpp"
#include "core/scene/checks.hpp"

namespace stoss::scene::detail {

/// Validates a file mesh member (`mesh` has "file" or "id"), reads the file and checks every selected element
/// (det J0 > 0 at each Gauss point). Returns the body's surface names (nullopt when the mesh is invalid);
/// surfaces of the file without a face on the body are noted in checker.surface_notes under
/// "<body>/<surface>", so that a reference to one says why it is missing; its node sets go to
/// checker.node_sets (a boundary entry may name one).
std::optional<std::set<std::string>> check_file_mesh(json& mesh, const std::string& pointer,
                                                     const std::optional<std::string>& body_name,
                                                     Checker& checker);

/// The body mesh of a validated file mesh member.
mesh::BodyMesh file_body_mesh(const json& mesh, const MeshFiles& mesh_files);

}  // namespace stoss::scene::detail
