#pragma once
/// @file Mesh generators: primitives a scene names instead of listing nodes (docs/scene.md).

#include <Eigen/Core>
#include <array>

#include "core/mesh/mesh.hpp"

namespace stoss::mesh {

/// Structured hex8 grid of the box [min, max] with divisions[a] elements along axis a.
/// @note Node (i, j, k) has index i + (nx+1)(j + (ny+1)k); elements follow docs/theory.md §1.1
///       (local ξ, η, ζ along x, y, z), so det J0 > 0.
/// @note Surfaces `xmin xmax ymin ymax bottom top` (bottom: z = min.z, top: z = max.z), quads in
///       outward order: (b−a)×(d−a) points out of the box.
/// @throws std::invalid_argument unless max > min componentwise and every division ≥ 1.
BodyMesh box(const Eigen::Vector3d& min, const Eigen::Vector3d& max, const std::array<int, 3>& divisions);

/// Hollow sphere as a cube-sphere shell (docs/theory.md §7): 6 patches of divisions × divisions
/// equiangular cells, `layers` element layers between the radii.
/// @note Node layers at r_k = inner + k (outer − inner)/layers; nodes shared by patches are merged
///       (tolerance 1e-9 × outer_radius). divisions = 6, layers = 2 gives 654 nodes, 432 hex8.
/// @note Surfaces `outer` (normals away from the centre) and `inner` (normals towards the centre,
///       i.e. out of the material), quads in outward order.
/// @throws std::invalid_argument unless outer_radius > inner_radius > 0, divisions ≥ 1, layers ≥ 1.
BodyMesh hollow_sphere(const Eigen::Vector3d& center, double outer_radius, double inner_radius, int divisions,
                       int layers);

/// Half the edge of the solid sphere's core cube, as a fraction of its radius.
inline constexpr double sphere_core_fraction = 0.4;
/// Element layers of each of the solid sphere's caps: about as thick as the core's elements are wide.
int sphere_layers(int divisions);

/// How the solid sphere is refined and cut.
struct SphereOptions {
  /// κ ≥ 0 (at most 10): the grid parameter s ∈ [−1, 1] across the core and every cap is mapped through
  /// sinh(κ s)/sinh(κ), so elements are κ/sinh(κ) times as wide near the six poles ±x, ±y, ±z (0.30 at κ = 3)
  /// and wider at the caps' corners; 0 is uniform. For a body pressed at a pole (Hertz).
  double grading = 0;
  /// κ_r ≥ 0 (at most 10): the caps' layers at s_k = 1 − sinh(κ_r (1 − k/L))/sinh(κ_r) of the way out, so the
  /// outermost layer is about κ_r/sinh(κ_r) times as thick as the innermost; 0 is uniform.
  double radial_grading = 0;
  /// Only the quarter x ≥ c_x, y ≥ c_y (even divisions), with the cut planes as surfaces `xmin` and `ymin`,
  /// for a model on symmetry supports.
  bool quarter = false;
};

/// Solid sphere of hexahedra (docs/theory.md §5b.7): a core cube of half edge 0.4 R (sphere_core_fraction) in
/// divisions³ elements, and on each of its six faces a cap of divisions × divisions ×
/// sphere_layers(divisions) elements along straight lines from the cube's face grid to the equiangular
/// cube-sphere grid on the sphere (the `outer` grid of hollow_sphere when not graded). Nodes shared by the
/// parts are merged (tolerance 1e-9 R).
/// @note Surface `outer` (normals away from the centre) and, for a quarter, `xmin` and `ymin`; quads in
/// outward
///       order.
/// @throws std::invalid_argument unless radius > 0, divisions >= 1 (even for a quarter), and both gradings
/// are
///         in [0, 10].
BodyMesh sphere(const Eigen::Vector3d& center, double radius, int divisions,
                const SphereOptions& options = {});

}  // namespace stoss::mesh
