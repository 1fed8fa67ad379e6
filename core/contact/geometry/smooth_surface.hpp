#pragma once
/// @file The smooth master surface (docs/smooth_master_surface.md §2): one uniform cubic B-spline
/// patch per master face over its 4×4 node neighbourhood, with ghost nodes reflected across a
/// surface rim. C² where four faces meet at every node; it reproduces a flat uniform grid exactly and
/// interpolates the rim of a flat plate. Points stay linear in the master nodes (tensor_patch.hpp).

#include <string>
#include <vector>

#include "core/contact/geometry/tensor_patch.hpp"
#include "core/mesh/mesh.hpp"

namespace stoss::contact {

/// The patches of a surface, or why it cannot carry one.
struct SmoothSurface {
  std::vector<TensorPatch> patches;  ///< one per face, same order
  std::string problem;               ///< empty if the surface qualifies
  bool ok() const { return problem.empty(); }
};

/// Builds the smooth surface of `faces` (outward-ordered quads, mesh.hpp). The surface must be a
/// consistently oriented manifold: every edge in at most two faces, traversed in opposite directions;
/// every interior node in exactly four faces (no extraordinary vertex); every rim node in one or two.
/// Otherwise `problem` names the first node or edge that breaks the rule and `patches` is empty.
SmoothSurface smooth_surface(const std::vector<mesh::Quad>& faces);

/// The faceted surface of the same faces: one bilinear patch per face.
std::vector<TensorPatch> faceted_patches(const std::vector<mesh::Quad>& faces);

}  // namespace stoss::contact
