#pragma once
/// @file Validated scene JSON (defaults filled in) → Model.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/mesh/mesh.hpp"
#include "core/model/model.hpp"
#include "core/scene/scene.hpp"

namespace stoss::scene::detail {

/// The det J0 (docs/theory.md (1.1)–(1.2)) that makes an element unusable, nullopt when every one of its
/// 2×2×2 Gauss points has a det J0 that is > 0, finite and a normal double: the smallest when one is <= 0,
/// else one that is infinite, NaN or subnormal (coordinates of 1e200 or 1e-105 give such volumes; the
/// integrator would fail at step 1).
std::optional<double> unusable_jacobian_determinant(const std::vector<Eigen::Vector3d>& nodes,
                                                    const mesh::Hex& element);
/// What is wrong with an element whose det J0 is `det` (a value unusable_jacobian_determinant returned).
std::string jacobian_problem(double det);

/// The body mesh a validated `mesh` member describes (box, hollow_sphere or inline). An inline mesh
/// gets the surface "boundary" (all boundary faces) unless it names one itself.
/// A file mesh ("file" or "id") is read from `mesh_files` (see file_mesh.hpp).
mesh::BodyMesh body_mesh(const nlohmann::json& mesh, const MeshFiles& mesh_files = {});

/// The Model of a validated scene; model.scene = `scene`, bodies added to the mesh in order.
model::Model build_model(const nlohmann::json& scene, const MeshFiles& mesh_files = {});

}  // namespace stoss::scene::detail
