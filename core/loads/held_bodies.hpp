#pragma once
/// @file Which bodies of a static scene something holds (issue 23 §3; docs/theory.md §5b.8): the rigid
/// motions that the supports, prescribed motions and contacts with held bodies leave free. A static step
/// has no inertia, so a free rigid mode is a singular tangent; the scene validator refuses it instead.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace stoss::loads {

/// The rigid motion X ↦ translation + rotation × (X − centroid) of one body (its nodes' centroid).
struct RigidMode {
  Eigen::Vector3d translation, rotation;
};

/// A node held along one direction: a support or a prescribed motion holds e_k, a contact its normal.
struct HeldDirection {
  int node;
  Eigen::Vector3d direction;
};

/// A contact pair by its surfaces ("body/surface"); the masters belong to one body.
struct ContactSurfaces {
  std::string slave;
  std::vector<std::string> master;
  /// Per node of the mesh, whether it touches the other side (only those hold); empty: every node does.
  std::vector<char> touching;
};

/// A body and a basis of the rigid motions nothing holds (empty: held).
struct BodyFreedom {
  int body = 0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::vector<RigidMode> free_modes;
  bool held() const { return free_modes.empty(); }
};

/// Per body, the rigid modes that neither the held dofs `fixed` (3 per node) nor `extra` remove (5b.9).
/// The basis is in reduced echelon form over (translation x, y, z, rotation x, y, z), so modes that are
/// free one by one come out one by one ("translation along x").
std::vector<BodyFreedom> free_rigid_modes(const mesh::Mesh& mesh, const std::vector<char>& fixed,
                                          const std::vector<HeldDirection>& extra = {});

/// As above, where a contact pair between a held body and one that is not yet held also holds the other
/// body's surface nodes along that surface's normals (normal direction only), repeated until no more
/// bodies become held (issue 23 §3). @throws std::out_of_range naming a surface the mesh lacks.
std::vector<BodyFreedom> free_rigid_modes(const mesh::Mesh& mesh, const std::vector<char>& fixed,
                                          const std::vector<ContactSurfaces>& contact);

/// "translation along x", "rotation about z through (0.5, 0.5, 1)", "translation along (0.6, 0.8, 0)".
std::string describe(const RigidMode& mode, const Eigen::Vector3d& centroid);

/// The validator's rule for a body that is not held: "body 'block' is free to move as a rigid body (…):
/// a static scene needs supports, prescribed motions or contacts with held bodies that remove every rigid
/// mode". Empty when the body is held.
std::string rigid_mode_rule(const mesh::Mesh& mesh, const BodyFreedom& freedom);

}  // namespace stoss::loads
