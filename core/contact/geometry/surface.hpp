#pragma once
/// @file The two sides of one contact pair: slave nodes and master faces taken from named mesh
/// surfaces ("body/surface"), with the per-face sizes the search and the measures use
/// (docs/theory.md §3.1, §3.4).

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "core/contact/geometry/tensor_patch.hpp"
#include "core/contact/types.hpp"
#include "core/mesh/mesh.hpp"

namespace stoss::contact {

/// Slave nodes and master segments of one pair (global node numbering of the Mesh).
/// @note `face_size` is the mean edge length of a master face in the reference configuration;
///       `tributary_area` is a quarter of the reference area of every slave-surface quad that
///       touches the node (the area a nodal contact force is spread over for `contact_pressure`).
struct PairSurfaces {
  std::vector<int> slave_nodes;        ///< sorted, unique
  std::vector<double> tributary_area;  ///< per slave node
  std::vector<mesh::Quad> faces;       ///< master faces, outward order (§1.1)
  std::vector<double> face_size;       ///< per master face
  double mean_face_size = 0;
  /// Smooth master surface: one patch per face (smooth_surface.hpp); empty for the faceted surface,
  /// whose face f is the bilinear segment of faces[f].
  std::vector<TensorPatch> patches;
  bool smooth() const { return !patches.empty(); }
};

/// Collects the pair's surfaces from the mesh; throws std::out_of_range naming a missing surface and
/// std::invalid_argument if a surface is empty.
PairSurfaces pair_surfaces(const mesh::Mesh& mesh, const std::string& slave, const std::string& master);

/// The master nodes an element on face f couples to: the patch's nodes on a smooth surface, the face's
/// four nodes otherwise.
std::vector<int> master_nodes(const PairSurfaces& s, int face);

/// Global dofs of a slave node and the master nodes of face f (slave first, 3 per node).
std::vector<int> element_dofs(int slave, const PairSurfaces& s, int face);

/// Positions y_1 … y_4 of a face (rows) taken from stacked positions x.
SegmentNodes face_positions(const mesh::Quad& face, const Eigen::VectorXd& x);

/// Global dofs of the element vector [x_s; y_1; …; y_4] (docs/theory.md §3.3), 15 entries.
std::array<int, 15> element_dofs(int slave, const mesh::Quad& face);

/// The element vector [x_s; y_1; …; y_4] taken from stacked positions x.
Vector15 element_positions(int slave, const mesh::Quad& face, const Eigen::VectorXd& x);

}  // namespace stoss::contact
