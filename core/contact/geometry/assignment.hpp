#pragma once
/// @file Narrow phase of the contact search (docs/theory.md §3.4): which master face a slave node
/// belongs to, with a defined outcome at edges, corners and when no face accepts it.

#include <Eigen/Core>
#include <span>

#include "core/contact/geometry/projection.hpp"
#include "core/contact/geometry/surface.hpp"

namespace stoss::contact {

/// Tolerances of §3.4.
struct NarrowPhase {
  static constexpr double eps_xi = 1e-6;          ///< ξ ∈ [−1−ε_ξ, 1+ε_ξ]² accepts
  static constexpr double eps_ext = 0.05;         ///< retry tolerance when no face accepts
  static constexpr double gap_tie = 1e-12;        ///< |g_N| equal within this × face size: a tie
  static constexpr double xi_tie = 1e-13;         ///< |ξ|_∞ equal within this: a tie
  static constexpr double max_depth_ratio = 0.5;  ///< g_max = this × face size
};

/// A slave node's projection onto one master face.
struct FaceProjection {
  int face = -1;          ///< −1: no face accepts the node
  bool extended = false;  ///< accepted only with ε_ext
  Projection projection;
  bool found() const { return face >= 0; }
};

/// Whether a projection accepts the node (§3.4): the CPP converged, ξ ∈ [−1−eps, 1+eps]² and
/// g_N > −g_max (a projection through the body from its far side is rejected).
bool accepts(const Projection& p, double eps, double g_max);

/// True if a is the better face for the node: smaller |g_N|; tie (|Δ|g_N|| ≤ gap_tie × size):
/// smaller |ξ|_∞; tie (≤ xi_tie): lower face id. Deterministic for points on shared edges and nodes.
bool better(const FaceProjection& a, const FaceProjection& b, double size);

/// The best face among `faces` (candidate ids) for the slave at position `slave` (§3.4): CPP from
/// ξ = 0 on each, accept with ε_ξ; if none accepts, retry with ε_ext. `skip` is left out (−1: none).
/// Returns face = −1 if still none accepts (the NTS blind spot at convex edges, or a node far from
/// every candidate): no contact element for that node.
FaceProjection best_face(const Eigen::Vector3d& slave, std::span<const int> faces, const PairSurfaces& s,
                         const Eigen::VectorXd& x, int skip = -1);

/// The projection of the slave onto one given face (CPP from `xi_start`), whether or not it accepts.
FaceProjection project_on(const Eigen::Vector3d& slave, int face, const PairSurfaces& s,
                          const Eigen::VectorXd& x,
                          const Eigen::Vector2d& xi_start = Eigen::Vector2d::Zero());

}  // namespace stoss::contact
