#include "core/scene/held_check.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/contact/geometry/projection.hpp"
#include "core/contact/geometry/surface.hpp"
#include "core/loads/held_bodies.hpp"

namespace stoss::scene::detail {
namespace {

/// 3 flags per node: the directions some boundary entry holds (supports and prescribed motions alike).
std::vector<char> held_dofs(const model::Model& m) {
  std::vector<char> fixed(m.dof_count(), 0);
  for (const model::Boundary& b : m.boundary)
    for (int node : m.mesh.named_nodes(b.surface))
      for (int k = 0; k < 3; ++k)
        if (b.fix[k]) fixed[3 * node + k] = 1;
  return fixed;
}

/// A gap up to this fraction of a face's size touches (as the static contact term's closes_touching).
constexpr double touching_gap = 1e-8;

/// Marks in `touching` the nodes of `side` that touch a face of `other` at t = 0: a converged closest-point
/// projection (docs/theory.md §3.2) inside the face with a gap of at most touching_gap of its size.
void mark_touching(const mesh::Mesh& mesh, const std::string& side, const std::string& other,
                   std::vector<char>& touching) {
  const Eigen::VectorXd X = mesh.reference_positions();
  const std::vector<int> candidates = mesh.surface_nodes(side);
  for (const mesh::Quad& face : mesh.surface(other)) {
    Eigen::AlignedBox3d box;
    for (int I : face) box.extend(mesh.nodes[I]);
    const double size = box.diagonal().norm() / std::sqrt(2.0), reach = touching_gap * size;
    box.extend(box.min() - Eigen::Vector3d::Constant(reach))
        .extend(box.max() + Eigen::Vector3d::Constant(reach));
    const contact::SegmentNodes nodes = contact::face_positions(face, X);
    for (int I : candidates) {
      if (touching[I] || !box.contains(mesh.nodes[I])) continue;
      const contact::Projection p = contact::closest_point_projection(mesh.nodes[I], nodes);
      if (p.converged && contact::inside(p.xi, 1e-6) && p.gap <= reach) touching[I] = 1;
    }
  }
}

/// The pairs as held_bodies sees them: each side holds only where it touches the other at t = 0.
std::vector<loads::ContactSurfaces> touching_pairs(const model::Model& m) {
  std::vector<loads::ContactSurfaces> out;
  for (const model::ContactPair& p : m.contact) {
    std::vector<char> touching(m.mesh.node_count(), 0);
    mark_touching(m.mesh, p.slave, p.master, touching);
    mark_touching(m.mesh, p.master, p.slave, touching);
    out.push_back({p.slave, {p.master}, std::move(touching)});
  }
  return out;
}

}  // namespace

std::vector<Issue> unheld_bodies(const model::Model& m) {
  if (m.time.scheme != model::Scheme::equilibrium) return {};
  std::vector<Issue> issues;
  for (const loads::BodyFreedom& f : loads::free_rigid_modes(m.mesh, held_dofs(m), touching_pairs(m)))
    if (!f.held()) issues.push_back({"/bodies/" + std::to_string(f.body), loads::rigid_mode_rule(m.mesh, f)});
  return issues;
}

}  // namespace stoss::scene::detail
