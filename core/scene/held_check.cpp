#include "core/scene/held_check.hpp"

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

}  // namespace

std::vector<Issue> unheld_bodies(const model::Model& m) {
  if (m.time.scheme != model::Scheme::equilibrium) return {};
  std::vector<loads::ContactSurfaces> contact;
  for (const model::ContactPair& p : m.contact) contact.push_back({p.slave, {p.master}});
  std::vector<Issue> issues;
  for (const loads::BodyFreedom& f : loads::free_rigid_modes(m.mesh, held_dofs(m), contact))
    if (!f.held()) issues.push_back({"/bodies/" + std::to_string(f.body), loads::rigid_mode_rule(m.mesh, f)});
  return issues;
}

}  // namespace stoss::scene::detail
