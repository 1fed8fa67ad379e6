#pragma once
/// @file Validated scene JSON (defaults filled in) → Model.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "core/mesh/mesh.hpp"
#include "core/model/model.hpp"
#include "core/scene/scene.hpp"

namespace stoss::scene::detail {

/// Smallest det J0 over the 2×2×2 Gauss points of one element (docs/theory.md (1.1)–(1.2)).
double min_jacobian_determinant(const std::vector<Eigen::Vector3d>& nodes, const mesh::Hex& element);

/// The body mesh a validated `mesh` member describes (box, hollow_sphere or inline). An inline mesh
/// gets the surface "boundary" (all boundary faces) unless it names one itself.
/// A file mesh ("file" or "id") is read from `mesh_files` (see file_mesh.hpp).
mesh::BodyMesh body_mesh(const nlohmann::json& mesh, const MeshFiles& mesh_files = {});

/// The Model of a validated scene; model.scene = `scene`, bodies added to the mesh in order.
model::Model build_model(const nlohmann::json& scene, const MeshFiles& mesh_files = {});

}  // namespace stoss::scene::detail
