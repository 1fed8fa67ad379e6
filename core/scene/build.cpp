#include "core/scene/build.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "core/fem/hex8.hpp"
#include "core/mesh/generators.hpp"
#include "core/scene/checks.hpp"
#include "core/scene/file_mesh.hpp"

namespace stoss::scene::detail {
namespace {

using nlohmann::json;

Eigen::Vector3d vector3(const json& v) {
  return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
}

mesh::BodyMesh inline_mesh(const json& m) {
  mesh::BodyMesh body;
  for (const json& x : m["nodes"]) body.nodes.push_back(vector3(x));
  body.hex8 = m["hex8"].get<std::vector<mesh::Hex>>();
  for (const auto& [name, quads] : m["surfaces"].items())
    body.surfaces[name] = quads.get<std::vector<mesh::Quad>>();
  if (!body.surfaces.contains("boundary")) body.surfaces["boundary"] = mesh::boundary_faces(body.hex8);
  return body;
}

model::BodySpec body_spec(const json& b) {
  model::BodySpec spec;
  spec.name = b["name"].get<std::string>();
  const json& m = b["material"];
  spec.material = {m["model"].get<std::string>(), m["youngs_modulus"].get<double>(),
                   m["poisson_ratio"].get<double>(), m["density"].get<double>()};
  spec.initial_velocity = vector3(b["initial_velocity"]);
  spec.initial_angular_velocity = vector3(b["initial_angular_velocity"]);
  if (b.contains("center")) spec.center = vector3(b["center"]);
  return spec;
}

model::Boundary boundary(const json& e) {
  const auto fix = e["fix"].get<std::string>();
  model::Boundary b{e["surface"].get<std::string>(),
                    {fix.find('x') != std::string::npos, fix.find('y') != std::string::npos,
                     fix.find('z') != std::string::npos}};
  if (e.contains("displacement")) b.displacement = vector3(e["displacement"]);
  if (e.contains("amplitude")) b.amplitude = e["amplitude"].get<std::vector<std::array<double, 2>>>();
  return b;
}

model::Load load(const json& e) {
  model::Load l;
  l.surface = e["surface"].get<std::string>();
  if (e.contains("traction")) {
    l.kind = model::Load::Kind::traction;
    l.traction = vector3(e["traction"]);
  } else {
    l.pressure = e["pressure"].get<double>();
  }
  if (e.contains("amplitude")) l.amplitude = e["amplitude"].get<std::vector<std::array<double, 2>>>();
  return l;
}

/// A contact side as one "body/surface" name: the name itself, or for a list the union surface the mesh gets
/// (mesh::Mesh::add_surface_union), which the contact code then sees like any named surface.
std::string contact_side(const json& side, mesh::Mesh& mesh) {
  if (side.is_string()) return side.get<std::string>();
  return mesh.add_surface_union(side.get<std::vector<std::string>>());
}

model::ContactPair contact_pair(const json& e, mesh::Mesh& mesh) {
  model::ContactPair pair;
  pair.slave = contact_side(e["slave"], mesh);
  pair.master = contact_side(e["master"], mesh);
  pair.enforcement =
      e["enforcement"] == "penalty" ? model::Enforcement::penalty : model::Enforcement::lagrange;
  pair.discretization = e.value("discretization", "") == "mortar" ? model::Discretization::mortar
                                                                  : model::Discretization::node_to_segment;
  pair.friction = e["friction"].get<double>();
  pair.impact = e["impact"] == "exact"                 ? model::ImpactMode::exact
                : e["impact"] == "velocity_correction" ? model::ImpactMode::velocity_correction
                : e["impact"] == "located"             ? model::ImpactMode::located
                                                       : model::ImpactMode::persist;
  pair.switch_hysteresis = e["switch_hysteresis"].get<double>();
  pair.switch_gap = e.value("switch_gap", "") == "keep" ? model::SwitchGap::keep : model::SwitchGap::clamp;
  if (e.contains("normal_stiffness")) pair.normal_stiffness = e["normal_stiffness"].get<double>();
  if (e.contains("tangential_stiffness")) pair.tangential_stiffness = e["tangential_stiffness"].get<double>();
  pair.normal_traction = e["normal_traction"] == "midpoint" ? model::NormalTraction::midpoint
                                                            : model::NormalTraction::discrete_derivative;
  return pair;
}

model::TimeSpec time_spec(const json& t) {
  model::TimeSpec spec;
  spec.scheme = model::scheme_from_string(t["scheme"].get<std::string>()).value();
  spec.step = t["step"].get<double>();
  spec.end = t["end"].get<double>();
  if (t.contains("alpha")) spec.alpha = t["alpha"].get<double>();
  if (t.contains("rho_infinity")) spec.rho_infinity = t["rho_infinity"].get<double>();
  if (t.contains("tolerance")) {  // validation filled in min_step and max_step
    spec.tolerance = t["tolerance"].get<double>();
    spec.min_step = t["min_step"].get<double>();
    spec.max_step = t["max_step"].get<double>();
  }
  return spec;
}

}  // namespace

std::optional<double> unusable_jacobian_determinant(const std::vector<Eigen::Vector3d>& nodes,
                                                    const mesh::Hex& element) {
  fem::Matrix83 X;
  for (int I = 0; I < 8; ++I) X.row(I) = nodes[element[I]].transpose();
  const std::array<double, 8> det = fem::jacobian_determinants(X);  // (1.2)
  const double smallest = *std::min_element(det.begin(), det.end());
  if (smallest <= 0) return smallest;
  for (double d : det)
    if (!std::isnormal(d)) return d;  // inf, NaN or subnormal
  return std::nullopt;
}

std::string jacobian_problem(double det) {
  const std::string value = "det J0 = " + rounded_text(det) + " at a Gauss point";
  if (det <= 0) return "inverted or degenerate hexahedron, " + value + " (must be > 0; check the node order)";
  if (!std::isfinite(det))
    return value + ": the element's volume is not a finite number (coordinates too large? scale the mesh)";
  return value +
         " is below the smallest normal double (2.2e-308): the element is too small to compute with "
         "(coordinates too small? scale the mesh)";
}

/// A generated body with its whole boundary as the surface "boundary", like every other mesh.
mesh::BodyMesh with_boundary(mesh::BodyMesh body) {
  body.surfaces["boundary"] = mesh::boundary_faces(body.hex8);
  return body;
}

mesh::BodyMesh body_mesh(const json& m, const MeshFiles& mesh_files) {
  if (m.contains("file") || m.contains("id")) return file_body_mesh(m, mesh_files);
  if (m.contains("box")) {
    const json& b = m["box"];
    return with_boundary(
        mesh::box(vector3(b["min"]), vector3(b["max"]), b["divisions"].get<std::array<int, 3>>()));
  }
  if (m.contains("hollow_sphere")) {
    const json& s = m["hollow_sphere"];
    return with_boundary(mesh::hollow_sphere(vector3(s["center"]), s["outer_radius"].get<double>(),
                                             s["inner_radius"].get<double>(), s["divisions"].get<int>(),
                                             s["layers"].get<int>()));
  }
  return inline_mesh(m);
}

model::Model build_model(const json& scene, const MeshFiles& mesh_files) {
  model::Model m;
  m.name = scene["name"].get<std::string>();
  m.scene = scene;
  for (const json& b : scene["bodies"]) {
    m.mesh.add_body(b["name"].get<std::string>(), body_mesh(b["mesh"], mesh_files));
    m.bodies.push_back(body_spec(b));
  }
  for (const json& e : scene["boundary"]) m.boundary.push_back(boundary(e));
  for (const json& e : scene["loads"]) m.loads.push_back(load(e));
  for (const json& e : scene["contact"]) m.contact.push_back(contact_pair(e, m.mesh));
  const Eigen::Vector3d g = vector3(scene["gravity"]);
  if (g.norm() > 0) m.gravity = g;
  m.time = time_spec(scene["time"]);
  for (model::ContactPair& pair : m.contact)
    pair.closes_touching = m.time.scheme == model::Scheme::equilibrium;
  m.solver = {scene["solver"]["tolerance"].get<double>(), scene["solver"]["max_iterations"].get<int>(),
              model::linear_solver_from_string(scene["solver"]["linear"].get<std::string>()).value()};
  m.solver.ranks = scene["solver"].value("ranks", 1);
  const json& output = scene["output"];
  m.output.every = output.value("every", 1);
  if (output.contains("interval")) m.output.interval = output["interval"].get<double>();
  m.output.checkpoint_seconds = output.value("checkpoint_seconds", 60.0);
  m.output.checkpoint_every = output.value("checkpoint_every", 0);
  m.effects = model::resolve_effects(m);
  return m;
}

}  // namespace stoss::scene::detail
