#pragma once
// Quad grids for the smooth-surface tests: nx × ny faces, node (i, j) at index i + (nx + 1) j,
// faces ordered counter-clockwise seen from +z (outward normal up).
#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "core/contact/geometry/smooth_surface.hpp"
#include "core/mesh/generators.hpp"
#include "core/mesh/mesh.hpp"

namespace stoss::contact::test {

struct Grid {
  int nx = 0, ny = 0;
  double spacing = 0.25;
  std::vector<mesh::Quad> faces;
  Eigen::VectorXd x;

  int id(int i, int j) const { return i + (nx + 1) * j; }
  int face(int i, int j) const { return i + nx * j; }
  Eigen::Vector3d node(int i, int j) const { return x.segment<3>(3 * id(i, j)); }

  template <class Shape>
  static Grid make(int nx, int ny, double spacing, Shape shape) {
    Grid g;
    g.nx = nx, g.ny = ny, g.spacing = spacing;
    g.x.resize(3 * (nx + 1) * (ny + 1));
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) g.x.segment<3>(3 * g.id(i, j)) = shape(i * spacing, j * spacing);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        g.faces.push_back({g.id(i, j), g.id(i + 1, j), g.id(i + 1, j + 1), g.id(i, j + 1)});
    return g;
  }
  /// A flat uniform grid in z = 0.
  static Grid flat(int nx, int ny, double spacing) {
    return make(nx, ny, spacing, [](double u, double v) { return Eigen::Vector3d(u, v, 0); });
  }
  /// The outer surface of a unit hollow sphere (cube-sphere: valence 3 at the 8 cube corners).
  static Grid sphere(int divisions) {
    const mesh::BodyMesh b = mesh::hollow_sphere({0, 0, 0}, 1.0, 0.8, divisions, 1);
    Grid g;
    g.spacing = 1.6 / divisions;
    g.faces = b.surfaces.at("outer");
    g.x.resize(3 * b.nodes.size());
    for (size_t I = 0; I < b.nodes.size(); ++I) g.x.segment<3>(3 * I) = b.nodes[I];
    return g;
  }
  /// A doubly curved, slightly irregular grid (a bump with uneven spacing).
  static Grid curved(int nx, int ny) {
    return make(nx, ny, 0.25, [](double u, double v) {
      return Eigen::Vector3d(u + 0.03 * std::sin(7 * v), v + 0.02 * std::cos(5 * u),
                             0.3 * std::sin(1.3 * u) * std::cos(1.1 * v));
    });
  }
};

/// A parameterised element case: a face of the curved 4 × 4 grid at (face_i, face_j) and ξ, its
/// bilinear face, or (sphere) the first face with an extraordinary corner at (u, v) = xi from it.
struct PatchCase {
  const char* name;
  int face_i, face_j;
  Eigen::Vector2d xi;
  bool bilinear = false, sphere = false;
};

/// The grid, the patch and the face coordinates ξ of a case.
struct PickedPatch {
  Grid grid;
  TensorPatch patch;
  Eigen::Vector2d xi;
};

inline PickedPatch pick(const PatchCase& c) {
  PickedPatch out{c.sphere ? Grid::sphere(4) : Grid::curved(4, 4), {}, c.xi};
  if (c.sphere) {
    for (const TensorPatch& p : smooth_surface(out.grid.faces).patches)
      if (p.pieces && !out.patch.pieces) out.patch = p;
    out.xi = detail::corner_rotation(out.patch.pieces->corner).transpose() *
             Eigen::Vector2d(2 * c.xi[0] - 1, 2 * c.xi[1] - 1);
  } else {
    const int f = out.grid.face(c.face_i, c.face_j);
    out.patch = c.bilinear ? bilinear_patch(out.grid.faces[f]) : smooth_surface(out.grid.faces).patches[f];
  }
  return out;
}

}  // namespace stoss::contact::test
