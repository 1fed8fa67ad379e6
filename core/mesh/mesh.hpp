#pragma once
/// @file Mesh: nodes, trilinear hexahedra and named quad surfaces of every body in a scene.

#include <Eigen/Core>
#include <array>
#include <map>
#include <string>
#include <vector>

namespace stoss::mesh {

using Hex = std::array<int, 8>;   ///< node indices in VTK_HEXAHEDRON order (docs/theory.md §1.1)
using Quad = std::array<int, 4>;  ///< face node indices, ordered so that (b−a)×(d−a) points outwards

/// One body's mesh with body-local node indices (what generators and importers produce).
struct BodyMesh {
  std::vector<Eigen::Vector3d> nodes;
  std::vector<Hex> hex8;
  std::map<std::string, std::vector<Quad>> surfaces;
  std::map<std::string, std::vector<int>> node_sets;  ///< named nodes (*NSET), sorted body-local indices
  std::string skipped_note;  ///< the mesh file's note on elements it read and left out; empty if none
};

/// A body's place inside the global Mesh. Surfaces hold global node indices.
struct Body {
  std::string name;
  int node_begin = 0, node_end = 0;        ///< [begin, end) in Mesh::nodes
  int element_begin = 0, element_end = 0;  ///< [begin, end) in Mesh::hex8
  std::map<std::string, std::vector<Quad>> surfaces;
  std::map<std::string, std::vector<int>> node_sets;  ///< sorted global node indices
  std::string skipped_note;                           ///< BodyMesh::skipped_note
};

/// All bodies of a scene in one node and element numbering.
struct Mesh {
  std::vector<Eigen::Vector3d> nodes;  ///< reference coordinates X_I
  std::vector<Hex> hex8;
  std::vector<int> element_body;  ///< body index of each element
  std::vector<Body> bodies;

  int node_count() const { return static_cast<int>(nodes.size()); }
  int element_count() const { return static_cast<int>(hex8.size()); }

  /// Appends a body, renumbering its nodes; returns the body index.
  int add_body(const std::string& name, const BodyMesh& body);
  /// Body index by name, or -1.
  int find_body(const std::string& name) const;
  /// Surface "body/surface"; throws std::out_of_range naming what is missing.
  const std::vector<Quad>& surface(const std::string& body_slash_surface) const;
  /// Adds the union of surfaces `body_slash_surfaces` (all "body/…" of one body) to that body as one surface
  /// named "body/a+b+…" and returns the name: faces in list order, a face named twice (same nodes) kept
  /// once. A single name is returned as it is. '+' is not allowed in surface names, so the union's name
  /// cannot clash with a named surface. Throws std::out_of_range / std::invalid_argument naming what is
  /// wrong.
  std::string add_surface_union(const std::vector<std::string>& body_slash_surfaces);
  /// Sorted unique node indices of a surface.
  std::vector<int> surface_nodes(const std::string& body_slash_surface) const;
  /// Node set "body/set" (sorted global indices); throws std::out_of_range naming what is missing.
  const std::vector<int>& node_set(const std::string& body_slash_set) const;
  /// The nodes a boundary condition names by "body/name": the surface's nodes when the body has a surface
  /// of that name, else its node set (an Abaqus *NSET). Throws std::out_of_range naming both kinds when
  /// neither exists.
  std::vector<int> named_nodes(const std::string& body_slash_name) const;
  /// Stacked reference coordinates (3 per node).
  Eigen::VectorXd reference_positions() const;
};

/// Faces that belong to exactly one element, in outward order (docs/theory.md §1.1).
std::vector<Quad> boundary_faces(const std::vector<Hex>& hex8);

/// The six faces of a hex8 in outward order: ζ−, ζ+, η−, η+, ξ−, ξ+.
std::array<Quad, 6> hex_faces(const Hex& h);

}  // namespace stoss::mesh
