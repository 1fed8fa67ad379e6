#include "core/run/problem.hpp"

#include <Eigen/Geometry>
#include <algorithm>

#include "core/loads/pressure_load.hpp"
#include "core/loads/traction_load.hpp"
#include "core/run/timing.hpp"

namespace stoss::run {

namespace {

double bounding_box_diagonal(const mesh::Mesh& mesh) {
  Eigen::Vector3d lo = mesh.nodes.front(), hi = mesh.nodes.front();
  for (const auto& p : mesh.nodes) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return std::max((hi - lo).norm(), 1e-300);
}

/// The scene's loads as terms (docs/theory.md §5b.2): a follower pressure or a dead traction on the faces.
std::unique_ptr<loads::SurfaceLoad> make_load(const model::Model& m, const model::Load& l) {
  const std::vector<mesh::Quad>& faces = m.mesh.surface(l.surface);
  loads::Amplitude amplitude(l.amplitude);
  if (l.kind == model::Load::Kind::pressure)
    return std::make_unique<loads::PressureLoad>(faces, l.pressure, std::move(amplitude));
  return std::make_unique<loads::TractionLoad>(faces, m.mesh.reference_positions(), l.traction,
                                               std::move(amplitude));
}

std::vector<char> fixed_dofs(const model::Model& m) {
  std::vector<char> fixed(m.dof_count(), 0);
  for (const model::Boundary& b : m.boundary)
    for (int node : m.mesh.named_nodes(b.surface))  // a surface or an *NSET
      for (int k = 0; k < 3; ++k)
        if (b.fix[k]) fixed[3 * node + k] = 1;
  return fixed;
}

/// The dofs each entry holds, a dof held by several entries given to the first.
std::vector<std::vector<int>> held_dofs_by_entry(const model::Model& m) {
  std::vector<char> taken(m.dof_count(), 0);
  std::vector<std::vector<int>> out;
  for (const model::Boundary& b : m.boundary) {
    std::vector<int>& dofs = out.emplace_back();
    for (int node : m.mesh.named_nodes(b.surface))
      for (int k = 0; k < 3; ++k)
        if (b.fix[k] && !taken[3 * node + k]) {
          taken[3 * node + k] = 1;
          dofs.push_back(3 * node + k);
        }
  }
  return out;
}

/// The moving supports (docs/theory.md (5b.9)): each held dof follows the entry it counts in; none if no
/// displacement is non-zero.
std::unique_ptr<PrescribedMotion> make_supports(const model::Model& m,
                                                const std::vector<std::vector<int>>& held) {
  if (!m.has_effect(model::effect::prescribed_motion)) return nullptr;
  const Eigen::VectorXd X = m.mesh.reference_positions();
  std::vector<PrescribedDof> dofs;
  std::vector<loads::Amplitude> amplitudes;
  for (size_t e = 0; e < m.boundary.size(); ++e) {
    amplitudes.emplace_back(m.boundary[e].amplitude);
    for (int dof : held[e])
      if (m.boundary[e].displacement[dof % 3] != 0)
        dofs.push_back({dof, X[dof], m.boundary[e].displacement[dof % 3], int(e)});
  }
  return std::make_unique<PrescribedMotion>(std::move(dofs), std::move(amplitudes));
}

/// v_I = v_0 + ω × (X_I − c), c the given centre or the body's centre of mass; zero on fixed dofs.
Eigen::VectorXd initial_velocity(const model::Model& m, const Problem& p, const Eigen::VectorXd& X) {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(X.size());
  const Eigen::VectorXd nodal_mass = p.mass * Eigen::VectorXd::Ones(X.size());
  for (size_t b = 0; b < m.bodies.size(); ++b) {
    const mesh::Body& body = m.mesh.bodies[b];
    const model::BodySpec& spec = m.bodies[b];
    Eigen::Vector3d com = Eigen::Vector3d::Zero();
    double mass = 0;
    for (int I = body.node_begin; I < body.node_end; ++I) {
      com += nodal_mass[3 * I] * X.segment<3>(3 * I);
      mass += nodal_mass[3 * I];
    }
    const Eigen::Vector3d center = spec.center.value_or(com / mass);
    for (int I = body.node_begin; I < body.node_end; ++I)
      v.segment<3>(3 * I) =
          spec.initial_velocity + spec.initial_angular_velocity.cross(X.segment<3>(3 * I) - center);
  }
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (p.fixed[i]) v[i] = 0;
  return v;
}

}  // namespace

std::vector<time::Term*> Problem::terms() const {
  std::vector<time::Term*> out{elasticity.get()};
  if (gravity) out.push_back(gravity.get());
  for (const auto& l : loads) out.push_back(l.get());
  if (supports) out.push_back(supports.get());
  for (const auto& c : contact) out.push_back(c.get());
  return out;
}

double Problem::external_work() const {
  double work = 0;
  for (const auto& l : loads) work += l->work();
  if (supports) work += supports->work();
  return work;
}

Eigen::Vector3d Problem::load_impulse() const {
  Eigen::Vector3d impulse = Eigen::Vector3d::Zero();
  for (const auto& l : loads) impulse += l->impulse();
  return impulse;
}

Eigen::Vector3d Problem::gravity_force() const {
  if (!gravity) return Eigen::Vector3d::Zero();
  return gravity->load().reshaped(3, gravity->load().size() / 3).rowwise().sum();
}

std::vector<Eigen::Vector3d> Problem::entry_reactions(const Eigen::VectorXd& reaction) const {
  std::vector<Eigen::Vector3d> out(held_dofs.size(), Eigen::Vector3d::Zero());
  if (reaction.size() == 0) return out;
  for (size_t e = 0; e < held_dofs.size(); ++e)
    for (int dof : held_dofs[e]) out[e][dof % 3] += reaction[dof];
  return out;
}

Problem build_problem(const model::Model& m) {
  const auto t0 = Clock::now();
  Problem p;
  for (const model::ContactPair& pair : m.contact) p.contact.push_back(contact::make_pair_term(m, pair));
  if (!m.contact.empty()) p.setup_contact_seconds = seconds_since(t0);
  const auto t1 = Clock::now();
  std::vector<fem::ElementGeometry> geometry = fem::precompute_mesh(m.mesh);  // the term keeps it
  std::vector<double> density;
  std::vector<std::shared_ptr<const fem::Material>> body_material, material;
  for (const model::BodySpec& body : m.bodies) body_material.push_back(fem::make_material(body.material));
  for (int body : m.mesh.element_body) {
    density.push_back(m.bodies[body].material.density);
    material.push_back(body_material[body]);
  }
  p.mass = contact::contact_mass(m, fem::assemble_mass(m.mesh, geometry, density));  // theory.md §4.6.1
  p.velocity_map = contact::massless_velocity_map(m);
  p.elasticity = std::make_unique<fem::ElasticityTerm>(m.mesh, std::move(geometry), std::move(material));
  if (m.has_effect(model::effect::gravity))
    p.gravity = std::make_unique<fem::GravityTerm>(p.mass, *m.gravity);
  for (const model::Load& l : m.loads) p.loads.push_back(make_load(m, l));
  p.fixed = fixed_dofs(m);
  p.held_dofs = held_dofs_by_entry(m);
  p.supports = make_supports(m, p.held_dofs);
  p.total_mass = p.mass.sum() / 3;
  p.length_scale = bounding_box_diagonal(m.mesh);
  p.setup_seconds = seconds_since(t1);
  return p;
}

time::State initial_state(const model::Model& m, const Problem& p) {
  time::State s;
  s.x = m.mesh.reference_positions();
  s.v = initial_velocity(m, p, s.x);
  s.a = Eigen::VectorXd::Zero(s.x.size());
  return s;
}

model::Frame frame_of(const time::State& s, const Problem& p) {
  model::Frame f{s.t, s.x, s.v, {}, {}, {}};
  if (!p.contact.empty()) {
    f.contact_pressure = Eigen::VectorXd::Zero(s.x.size() / 3);
    for (const auto& term : p.contact) term->contact_pressure(f.contact_pressure);  // lagrange_term.hpp
  }
  return with_stresses(std::move(f), p);
}

model::Frame with_stresses(model::Frame frame, const Problem& p) {
  p.elasticity->element_stresses(frame.position, frame.cauchy_stress, frame.von_mises);
  return frame;
}

}  // namespace stoss::run
