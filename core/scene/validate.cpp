#include "core/scene/validate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "core/fem/material.hpp"
#include "core/loads/amplitude.hpp"
#include "core/scene/build.hpp"
#include "core/scene/file_mesh.hpp"

namespace stoss::scene::detail {
namespace {

using Surfaces = std::optional<std::set<std::string>>;  ///< nullopt: the body's mesh is invalid
using SurfaceIndex = std::map<std::string, Surfaces>;   ///< body name → its surface names
const json zero3 = json::array({0, 0, 0});

void check_node_limit(double nodes, const std::string& p, Checker& c) {
  if (nodes > static_cast<double>(max_generated_nodes))
    c.fail(p,
           "must give at most " + std::to_string(max_generated_nodes) + " nodes, got " + number_text(nodes));
}

void check_divisions(json& divisions, const std::string& p, Checker& c) {
  if (!divisions.is_array() || divisions.size() != 3) {
    c.fail(p, "must be an array of 3 integers, got " + shown(divisions));
    return;
  }
  double nodes = 1;
  for (size_t a = 0; a < 3; ++a)
    if (const auto n = integer(divisions[a], child(p, a), at_least(1), c))
      nodes *= static_cast<double>(*n + 1);
  check_node_limit(nodes, p, c);
}

void check_box(json& box, const std::string& p, Checker& c) {
  if (!object_with(box, p, {"min", "max", "divisions"}, c)) return;
  const size_t start = c.mark();
  const auto low = vector3_field(box, "min", p, Presence::must(), c);
  const auto high = vector3_field(box, "max", p, Presence::must(), c);
  if (low && high && !(high->array() > low->array()).all())
    c.fail(child(p, "max"), "must be > min componentwise, got " + shown(box["max"]));
  json* divisions = member(box, "divisions", p, Presence::must(), c);
  if (divisions) check_divisions(*divisions, child(p, "divisions"), c);
  if (!low || !high || !divisions || c.mark() != start) return;
  // Every element of the grid has det J0 = hx hy hz / 8 (docs/theory.md (1.2), h the element's edges).
  double det = 1.0 / 8;
  for (int a = 0; a < 3; ++a) det *= ((*high)[a] - (*low)[a]) / (*divisions)[a].get<double>();
  if (!std::isnormal(det) || det <= 0) c.fail(p, "its elements would be unusable: " + jacobian_problem(det));
}

/// The unusable det J0 of a corner cell of the sphere's first patch, in its inner or outer element layer, if
/// one is: the cells of docs/theory.md §7 (p = normalize(e_x + tan(-π/4 + iΔ) e_y + tan(-π/4 + jΔ) e_z),
/// Δ = π / (2 divisions)) show there the overflow, the underflow, or a centre so far out that the radii are
/// lost in rounding, which every other cell shares within a factor of a few.
std::optional<double> sphere_corner_jacobian(const Eigen::Vector3d& center, double inner, double outer,
                                             long long d, long long layers) {
  const double quarter = std::atan(1.0), step = 2 * quarter / static_cast<double>(d);
  const auto node = [&](int i, int j, long long k) {
    const Eigen::Vector3d p(1, std::tan(-quarter + i * step), std::tan(-quarter + j * step));
    return Eigen::Vector3d(center +
                           (inner + static_cast<double>(k) * (outer - inner) / layers) * p.normalized());
  };
  for (const long long k : {0LL, layers - 1}) {
    const std::vector<Eigen::Vector3d> nodes = {node(0, 0, k),     node(1, 0, k),     node(1, 1, k),
                                                node(0, 1, k),     node(0, 0, k + 1), node(1, 0, k + 1),
                                                node(1, 1, k + 1), node(0, 1, k + 1)};
    if (const auto det = unusable_jacobian_determinant(nodes, {0, 1, 2, 3, 4, 5, 6, 7})) return det;
  }
  return std::nullopt;
}

void check_hollow_sphere(json& sphere, const std::string& p, Checker& c) {
  if (!object_with(sphere, p, {"center", "outer_radius", "inner_radius", "divisions", "layers"}, c)) return;
  const size_t start = c.mark();
  const auto center = vector3_field(sphere, "center", p, Presence::or_default(zero3), c);
  const auto inner = number_field(sphere, "inner_radius", p, Presence::must(), above(0), c);
  const auto outer = number_field(sphere, "outer_radius", p, Presence::must(), above(0), c);
  if (inner && outer && !(*outer > *inner))
    c.fail(child(p, "outer_radius"), "must be > inner_radius (" + shown(sphere["inner_radius"]) + "), got " +
                                         shown(sphere["outer_radius"]));
  const auto d = integer_field(sphere, "divisions", p, Presence::or_default(6), at_least(1), c);
  const auto layers = integer_field(sphere, "layers", p, Presence::or_default(2), at_least(1), c);
  if (d && layers) check_node_limit((6.0 * *d * *d + 2) * (*layers + 1), p, c);
  if (c.mark() != start || !center || !inner || !outer || !d || !layers) return;
  if (const auto det = sphere_corner_jacobian(*center, *inner, *outer, *d, *layers))
    c.fail(p, "its elements would be unusable: " + jacobian_problem(*det));
}

/// Rows of `width` node indices, each in [0, node_count) when the node count is known.
void check_index_rows(json& rows, const std::string& p, size_t width, std::optional<size_t> node_count,
                      Checker& c) {
  const Interval range =
      node_count ? between(0, static_cast<double>(*node_count) - 1, true, true) : at_least(0);
  for (size_t i = 0; i < rows.size(); ++i) {
    if (!rows[i].is_array() || rows[i].size() != width) {
      c.fail(child(p, i),
             "must be an array of " + std::to_string(width) + " node indices, got " + shown(rows[i]));
      continue;
    }
    for (size_t k = 0; k < width; ++k) integer(rows[i][k], child(child(p, i), k), range, c);
  }
}

std::optional<size_t> check_nodes(const json& nodes, const std::string& p, Checker& c) {
  if (!non_empty_array(nodes, p, c)) return std::nullopt;
  for (size_t i = 0; i < nodes.size(); ++i) vector3(nodes[i], child(p, i), c);
  return nodes.size();
}

void check_named_surfaces(json& surfaces, const std::string& p, std::optional<size_t> node_count,
                          std::set<std::string>& names, Checker& c) {
  if (!surfaces.is_object()) {
    c.fail(p, "must be an object, got " + shown(surfaces));
    return;
  }
  for (auto& [key, quads] : surfaces.items()) {
    const std::string q = child(p, key);
    if (!name(json(key), q, c) || !non_empty_array(quads, q, c)) continue;
    check_index_rows(quads, q, 4, node_count, c);
    names.insert(key);
  }
}

void check_jacobians(const json& mesh, const std::string& p, Checker& c) {
  std::vector<Eigen::Vector3d> nodes;
  for (const json& x : mesh["nodes"])
    nodes.emplace_back(x[0].get<double>(), x[1].get<double>(), x[2].get<double>());
  const json& hex8 = mesh["hex8"];
  for (size_t e = 0; e < hex8.size(); ++e) {
    const auto det = unusable_jacobian_determinant(nodes, hex8[e].get<mesh::Hex>());
    if (det)
      c.fail(child(child(p, "hex8"), e),
             *det <= 0 ? "det J0 must be > 0 at every Gauss point, got " + rounded_text(*det)
                       : jacobian_problem(*det));
  }
}

Surfaces check_inline_mesh(json& mesh, const std::string& p, Checker& c) {
  const size_t start = c.mark();
  std::optional<size_t> node_count;
  if (json* nodes = member(mesh, "nodes", p, Presence::must(), c))
    node_count = check_nodes(*nodes, child(p, "nodes"), c);
  json* hex8 = member(mesh, "hex8", p, Presence::must(), c);
  if (hex8 && non_empty_array(*hex8, child(p, "hex8"), c))
    check_index_rows(*hex8, child(p, "hex8"), 8, node_count, c);
  if (c.mark() == start) check_jacobians(mesh, p, c);
  std::set<std::string> names{"boundary"};
  if (json* surfaces = member(mesh, "surfaces", p, Presence::or_default(json::object()), c))
    check_named_surfaces(*surfaces, child(p, "surfaces"), node_count, names, c);
  return c.mark() == start ? Surfaces(names) : std::nullopt;
}

Surfaces check_mesh(json& mesh, const std::string& p, const std::optional<std::string>& body_name,
                    Checker& c) {
  if (!object_with(
          mesh, p,
          {"box", "hollow_sphere", "nodes", "hex8", "surfaces", "file", "id", "elements", "transform"}, c))
    return std::nullopt;
  const bool inline_mesh = mesh.contains("nodes") || mesh.contains("hex8") || mesh.contains("surfaces");
  if (mesh.contains("box") + mesh.contains("hollow_sphere") + inline_mesh + mesh.contains("file") +
          mesh.contains("id") !=
      1) {
    c.fail(p, "exactly one of box, hollow_sphere, nodes+hex8, file, id");
    return std::nullopt;
  }
  if (mesh.contains("file") || mesh.contains("id")) return check_file_mesh(mesh, p, body_name, c);
  for (const char* key : {"elements", "transform"})
    if (mesh.contains(key)) {
      c.fail(child(p, key), "only for a mesh read from a file (\"file\" or \"id\")");
      return std::nullopt;
    }
  const size_t start = c.mark();
  if (inline_mesh) return check_inline_mesh(mesh, p, c);
  if (mesh.contains("box")) {
    check_box(mesh["box"], child(p, "box"), c);
    if (c.mark() == start)  // "boundary": the body's whole boundary, as for every mesh (build.cpp)
      return std::set<std::string>{"xmin", "xmax", "ymin", "ymax", "bottom", "top", "boundary"};
  } else {
    check_hollow_sphere(mesh["hollow_sphere"], child(p, "hollow_sphere"), c);
    if (c.mark() == start) return std::set<std::string>{"outer", "inner", "boundary"};
  }
  return std::nullopt;
}

void check_material(json& m, const std::string& p, Checker& c) {
  if (!object_with(m, p, {"model", "youngs_modulus", "poisson_ratio", "density"}, c)) return;
  // Every model of fem::make_material takes E, ν and ρ (docs/scene.md, "Material").
  choice_field(m, "model", p, Presence::or_default("saint_venant_kirchhoff"), fem::material_models(), c);
  number_field(m, "youngs_modulus", p, Presence::must(), above(0), c);
  number_field(m, "poisson_ratio", p, Presence::must(), between(-1, 0.5, false, false), c);
  number_field(m, "density", p, Presence::must(), above(0), c);
}

struct NamedSurfaces {
  std::string name;
  Surfaces surfaces;
};

std::optional<NamedSurfaces> check_body(json& b, const std::string& p, Checker& c) {
  const std::initializer_list<std::string_view> fields{
      "name", "mesh", "material", "initial_velocity", "initial_angular_velocity", "center"};
  if (!object_with(b, p, fields, c)) return std::nullopt;
  const json* name_value = member(b, "name", p, Presence::must(), c);
  const auto body_name = name_value ? name(*name_value, child(p, "name"), c) : std::nullopt;
  Surfaces surfaces;
  if (json* m = member(b, "mesh", p, Presence::must(), c))
    surfaces = check_mesh(*m, child(p, "mesh"), body_name, c);
  if (json* m = member(b, "material", p, Presence::must(), c)) check_material(*m, child(p, "material"), c);
  vector3_field(b, "initial_velocity", p, Presence::or_default(zero3), c);
  vector3_field(b, "initial_angular_velocity", p, Presence::or_default(zero3), c);
  vector3_field(b, "center", p, Presence::may(), c);
  if (!body_name) return std::nullopt;
  return NamedSurfaces{*body_name, surfaces};
}

SurfaceIndex check_bodies(json& bodies, const std::string& p, Checker& c) {
  SurfaceIndex index;
  std::map<std::string, std::string> first_pointer;
  if (!non_empty_array(bodies, p, c)) return index;
  for (size_t i = 0; i < bodies.size(); ++i) {
    const auto body = check_body(bodies[i], child(p, i), c);
    if (!body) continue;
    const std::string name_pointer = child(child(p, i), "name");
    if (const auto [it, fresh] = first_pointer.try_emplace(body->name, name_pointer); !fresh) {
      c.fail(name_pointer, "must be unique, got " + shown(body->name) + " (also " + it->second + ")");
      continue;
    }
    index[body->name] = body->surfaces;
  }
  return index;
}

/// A "body/surface" reference to an existing surface; returns the body name when it names a body.
std::optional<std::string> check_surface_ref(const json& value, const std::string& p,
                                             const SurfaceIndex& index, Checker& c, bool node_sets = false) {
  const auto ref = string(value, p, c);
  if (!ref) return std::nullopt;
  const size_t slash = ref->find('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 == ref->size()) {
    c.fail(p, "must be of the form body/surface, got " + shown(value));
    return std::nullopt;
  }
  const std::string body = ref->substr(0, slash), surface = ref->substr(slash + 1);
  const auto it = index.find(body);
  if (it == index.end()) {
    c.fail(p, "no body named " + shown(body));
    return std::nullopt;
  }
  const auto sets = c.node_sets.find(body);
  const bool has_sets = node_sets && sets != c.node_sets.end() && !sets->second.empty();
  if (it->second && !it->second->contains(surface) && !(has_sets && sets->second.contains(surface))) {
    const auto list = [](const std::set<std::string>& names) {
      std::string known;
      for (const std::string& s : names) known += (known.empty() ? "" : ", ") + s;
      return known;
    };
    const auto note = c.surface_notes.find(*ref);
    c.fail(p, "body " + shown(body) + " has no surface " + (has_sets ? "or node set " : "") + shown(surface) +
                  " (it has " + list(*it->second) + (has_sets ? "; node sets " + list(sets->second) : "") +
                  ")" + (note != c.surface_notes.end() ? "; " + note->second : ""));
  }
  return body;
}

/// A contact side: one "body/surface" reference, or a non-empty list of them on one body without repeats
/// (their union, docs/scene.md "Contact"). Returns the body name when every reference was good.
std::optional<std::string> check_surface_refs(const json& value, const std::string& p,
                                              const SurfaceIndex& index, Checker& c) {
  if (!value.is_array()) return check_surface_ref(value, p, index, c);
  if (!non_empty_array(value, p, c)) return std::nullopt;
  const size_t start = c.mark();
  std::optional<std::string> body;
  std::map<std::string, std::string> first_pointer;
  for (size_t k = 0; k < value.size(); ++k) {
    const std::string at = child(p, k);
    const auto this_body = check_surface_ref(value[k], at, index, c);
    if (!this_body) continue;
    if (const auto [it, fresh] = first_pointer.try_emplace(value[k].get<std::string>(), at); !fresh)
      c.fail(at, "must not repeat a surface, got " + shown(value[k]) + " (also " + it->second + ")");
    if (!body)
      body = this_body;
    else if (*this_body != *body)
      c.fail(at, "must be a surface of body " + shown(*body) + " like " + child(p, 0) +
                     " (the surfaces of one list belong to one body), got " + shown(value[k]));
  }
  return c.mark() == start ? body : std::nullopt;
}

/// Whether the scene names time.scheme "static" (read before the time object is checked: pairs default by
/// it).
bool names_static(const json& scene) {
  return scene.is_object() && scene.contains("time") && scene["time"].is_object() &&
         scene["time"].value("scheme", json()) == "static";
}

/// What a mortar pair (docs/theory.md §4.7) cannot have, each at the pair's pointer: friction (mortar is
/// frictionless: issue 24 §5 is not reached), the penalty method (the mortar term has Lagrange multipliers
/// only) and the smooth master surface (mortar integrates on the mesh's faceted faces).
void check_mortar_pair(const json& e, const std::string& p, bool frictional, Checker& c) {
  const std::string mortar = "discretization \"mortar\" ";
  if (frictional)
    c.fail(p,
           mortar +
               "is frictionless (friction on mortar is not implemented): friction must be 0 with it, got " +
               shown(e["friction"]) + "; use discretization \"node_to_segment\" for friction");
  else if (e.value("enforcement", "") == "penalty")
    c.fail(p, mortar +
                  "enforces contact with Lagrange multipliers: enforcement must be \"lagrange\" with it, "
                  "got \"penalty\"");
  if (e.value("master_surface", "") == "smooth")
    c.fail(p, mortar +
                  "integrates on the faceted master surface (the mesh's bilinear faces, docs/theory.md "
                  "§4.7): master_surface must be \"faceted\" or absent with it, got \"smooth\"");
}

void check_contact_pair(json& e, const std::string& p, const SurfaceIndex& index, bool statics, Checker& c) {
  const std::initializer_list<std::string_view> fields{
      "slave",          "master",           "enforcement",          "discretization",
      "friction",       "impact",           "switch_hysteresis",    "switch_gap",
      "master_surface", "normal_stiffness", "tangential_stiffness", "normal_traction"};
  if (!object_with(e, p, fields, c)) return;
  const json* slave = member(e, "slave", p, Presence::must(), c);
  const json* master = member(e, "master", p, Presence::must(), c);
  const auto slave_body = slave ? check_surface_refs(*slave, child(p, "slave"), index, c) : std::nullopt;
  const auto master_body = master ? check_surface_refs(*master, child(p, "master"), index, c) : std::nullopt;
  if (slave_body && master_body && *slave_body == *master_body)
    c.fail(child(p, "master"), "must be on another body than slave, got " + shown(*master));
  const auto friction = number_field(e, "friction", p, Presence::or_default(0.0), at_least(0), c);
  const bool frictional = friction && *friction > 0;
  const auto enforcement =
      choice_field(e, "enforcement", p, Presence::or_default(frictional ? "penalty" : "lagrange"),
                   {"lagrange", "penalty"}, c);
  if (frictional && enforcement == "lagrange")
    c.fail(child(p, "enforcement"), "friction > 0 requires enforcement \"penalty\"");
  const auto discretization = choice_field(e, "discretization", p, Presence::or_default("node_to_segment"),
                                           {"node_to_segment", "mortar"}, c);
  if (discretization == "mortar") check_mortar_pair(e, p, frictional, c);
  // Static steps have no impacts: the gap closes (model::contact_scheme_conflict).
  choice_field(e, "impact", p, Presence::or_default(statics ? "exact" : "persist"),
               {"persist", "exact", "velocity_correction", "located"}, c);
  number_field(e, "switch_hysteresis", p, Presence::or_default(0.05), at_least(0), c);
  // Both resolved once the mesh exists (master_surface.hpp): the defaults depend on the surface.
  choice_field(e, "switch_gap", p, Presence::may(), {"clamp", "keep"}, c);
  choice_field(e, "master_surface", p, Presence::may(), {"smooth", "faceted"}, c);
  number_field(e, "normal_stiffness", p, Presence::may(), above(0), c);
  number_field(e, "tangential_stiffness", p, Presence::may(), above(0), c);
  choice_field(e, "normal_traction", p, Presence::or_default("discrete_derivative"),
               {"discrete_derivative", "midpoint"}, c);
}

void check_fix(const json& fix, const std::string& p, Checker& c) {
  const auto letters = string(fix, p, c);
  if (!letters) return;
  const std::set<char> distinct(letters->begin(), letters->end());
  const bool ok = !letters->empty() && distinct.size() == letters->size() &&
                  std::all_of(letters->begin(), letters->end(), [](char l) { return l >= 'x' && l <= 'z'; });
  if (!ok) c.fail(p, "must be distinct letters from \"xyz\", got " + shown(fix));
}

void check_amplitude(const json& a, const std::string& p, loads::AmplitudeUse use, Checker& c);

/// A prescribed displacement (docs/scene.md "boundary"): three finite numbers, non-zero only in the
/// directions `fix` holds.
void check_displacement(const json& u, const std::string& p, const json* fix, Checker& c) {
  if (u.is_array() && u.size() == 3)
    for (size_t k = 0; k < 3; ++k)
      if (u[k].is_number() && !std::isfinite(u[k].get<double>())) {
        c.fail(child(p, k), "must be a finite number, got " + shown(u[k]));
        return;
      }
  const auto value = vector3(u, p, c);
  if (!value || !fix || !fix->is_string()) return;
  const std::string held = fix->get<std::string>();
  for (int k = 0; k < 3; ++k)
    if ((*value)[k] != 0 && held.find(char('x' + k)) == std::string::npos)
      c.fail(child(p, size_t(k)), std::string("must be 0: fix does not hold direction ") + char('x' + k) +
                                      " (fix is " + shown(*fix) + "), got " + shown(u[k]));
}

void check_boundary_condition(json& e, const std::string& p, const SurfaceIndex& index, Checker& c) {
  if (!object_with(e, p, {"surface", "fix", "displacement", "amplitude"}, c)) return;
  if (const json* surface = member(e, "surface", p, Presence::must(), c))  // a surface or an *NSET
    check_surface_ref(*surface, child(p, "surface"), index, c, true);
  const json* fix = member(e, "fix", p, Presence::or_default("xyz"), c);
  if (fix) check_fix(*fix, child(p, "fix"), c);
  if (e.contains("displacement")) check_displacement(e["displacement"], child(p, "displacement"), fix, c);
  if (e.contains("amplitude"))
    check_amplitude(e["amplitude"], child(p, "amplitude"), loads::AmplitudeUse::displacement, c);
}

/// An amplitude [[t0, f0], [t1, f1], …] (docs/theory.md (5b.1)): pairs of finite numbers, times increasing.
void check_amplitude(const json& a, const std::string& p, loads::AmplitudeUse use, Checker& c) {
  if (!array(a, p, c)) return;
  std::vector<loads::Amplitude::Point> points;
  for (size_t i = 0; i < a.size(); ++i) {
    const json& point = a[i];
    if (!point.is_array() || point.size() != 2 || !point[0].is_number() || !point[1].is_number()) {
      c.fail(child(p, i), "must be a pair [time, factor] of numbers, got " + shown(point));
      return;
    }
    points.push_back({point[0].get<double>(), point[1].get<double>()});
  }
  if (const auto broken = loads::amplitude_rule_broken(points, use)) c.fail(p + broken->where, broken->rule);
}

/// A load (docs/scene.md "loads"): one surface, exactly one of pressure and traction, an optional amplitude.
void check_load(json& e, const std::string& p, const SurfaceIndex& index, Checker& c) {
  if (!object_with(e, p, {"surface", "pressure", "traction", "amplitude"}, c)) return;
  if (const json* surface = member(e, "surface", p, Presence::must(), c))
    check_surface_ref(*surface, child(p, "surface"), index, c);
  const bool pressure = e.contains("pressure"), traction = e.contains("traction");
  if (pressure == traction)
    c.fail(p, std::string("must give exactly one of \"pressure\" and \"traction\", got ") +
                  (pressure ? "both" : "neither"));
  const double largest = std::numeric_limits<double>::max();
  if (pressure)
    number_field(e, "pressure", p, Presence::must(), between(-largest, largest, true, true, "finite"), c);
  if (traction) vector3_field(e, "traction", p, Presence::must(), c);
  if (e.contains("amplitude"))
    check_amplitude(e["amplitude"], child(p, "amplitude"), loads::AmplitudeUse::load, c);
}

template <class CheckEntry>
void check_entries(json& scene, const char* key, const SurfaceIndex& index, CheckEntry check_entry,
                   Checker& c) {
  json* entries = member(scene, key, "", Presence::or_default(json::array()), c);
  if (!array(*entries, child("", key), c)) return;
  for (size_t i = 0; i < entries->size(); ++i) check_entry((*entries)[i], child(child("", key), i), index, c);
}

/// time.tolerance, min_step and max_step (docs/scene.md "Time"): the bounds of adaptive steps, defaults
/// step/1024 and end, only with a tolerance; `step` (the first step) inside them.
void check_step_control(json& t, const std::string& p, std::optional<double> step, std::optional<double> end,
                        Checker& c) {
  if (!t.contains("tolerance")) {
    for (const char* key : {"min_step", "max_step"})
      if (t.contains(key))
        c.fail(child(p, key), "is allowed only with time.tolerance (steps chosen by a tolerance)");
    return;
  }
  const size_t start = c.mark();
  number_field(t, "tolerance", p, Presence::must(), above(0), c);
  if (!step || !end) return;
  const auto low = number_field(t, "min_step", p, Presence::or_default(*step / 1024), above(0), c);
  const auto high = number_field(t, "max_step", p, Presence::or_default(*end), above(0), c);
  if (!low || !high || c.mark() != start) return;
  if (*low > *high)
    c.fail(child(p, "min_step"),
           "must be <= max_step (" + shown(t["max_step"]) + "), got " + shown(t["min_step"]));
  if (*low >= *end)
    c.fail(child(p, "min_step"), "must be < end (" + shown(t["end"]) + "), got " + shown(t["min_step"]));
  else if (*end / *low > 1e9)
    c.fail(child(p, "min_step"),
           "must give at most 1e9 steps, got end / min_step = " + number_text(*end / *low));
  if (c.mark() == start && (*step < *low || *step > *high))
    c.fail(child(p, "step"), "must be in [min_step, max_step] = [" + shown(t["min_step"]) + ", " +
                                 shown(t["max_step"]) + "] (the first step), got " + shown(t["step"]));
}

void check_time(json& t, const std::string& p, Checker& c) {
  if (!object_with(
          t, p, {"scheme", "step", "end", "alpha", "rho_infinity", "tolerance", "min_step", "max_step"}, c))
    return;
  std::vector<std::string> names;
  for (model::Scheme s : model::scene_schemes) names.push_back(model::to_string(s));
  const std::vector<std::string_view> schemes(names.begin(), names.end());
  const auto scheme = choice_field(t, "scheme", p, Presence::or_default("energy_momentum"), schemes, c);
  const auto step = number_field(t, "step", p, Presence::must(), above(0), c);
  const auto end = number_field(t, "end", p, Presence::must(), above(0), c);
  if (step && end && *end < *step)
    c.fail(child(p, "end"), "must be >= step (" + shown(t["step"]) + "), got " + shown(t["end"]));
  if (step && end && *end / *step > 1e9)
    c.fail(child(p, "step"), "must give at most 1e9 steps, got end / step = " + number_text(*end / *step));
  const Presence alpha = scheme == "hht" ? Presence::or_default(-0.05) : Presence::may();
  number_field(t, "alpha", p, alpha, between(-1.0 / 3, 0, true, true, "-1/3, 0"), c);
  const Presence rho = scheme == "generalized_alpha" ? Presence::or_default(0.9) : Presence::may();
  number_field(t, "rho_infinity", p, rho, between(0, 1, true, true), c);
  if (scheme == "static" && t.contains("tolerance")) {
    c.fail(child(p, "tolerance"),
           "is not allowed with scheme \"static\": load steps have no time-discretisation error to control "
           "(give the load levels by step and end, and amplitudes)");
    return;
  }
  check_step_control(t, p, step, end, c);
}

/// Static steps have no inertia (docs/theory.md §5b.6): a body there starts, and stays, at rest.
void check_static_bodies(const json& scene, Checker& c) {
  const json& bodies = scene["bodies"];
  if (!bodies.is_array()) return;
  const auto nonzero_vector = [](const json& v) {
    const auto number = [](const json& x) { return x.is_number(); };
    return v.is_array() && v.size() == 3 && std::all_of(v.begin(), v.end(), number) && v != zero3;
  };
  for (size_t i = 0; i < bodies.size(); ++i)
    for (const char* key : {"initial_velocity", "initial_angular_velocity"})
      if (bodies[i].is_object() && bodies[i].contains(key) && nonzero_vector(bodies[i][key]))
        c.fail(child(child(child("", "bodies"), i), key),
               "must be [0, 0, 0] with time.scheme \"static\" (no inertia: bodies are at rest), got " +
                   shown(bodies[i][key]));
}

void check_solver(json& s, const std::string& p, Checker& c) {
  if (!object_with(s, p, {"tolerance", "max_iterations", "max_wall_seconds", "linear", "ranks"}, c)) return;
  std::vector<std::string> names;
  for (model::LinearSolver l : model::all_linear_solvers) names.push_back(model::to_string(l));
  choice_field(s, "linear", p, Presence::or_default("auto"), {names.begin(), names.end()}, c);
  number_field(s, "tolerance", p, Presence::or_default(1e-10), between(0, 1e-3, false, true, "0, 1e-3"), c);
  integer_field(s, "max_iterations", p, Presence::or_default(25), between(1, 200, true, true), c);
  // Read by the job service only (a job's wall-time limit); the core ignores it.
  number_field(s, "max_wall_seconds", p, Presence::may(), between(0, 1e7, false, true, "0, 1e7"), c);
  // Absent means one rank, and is not filled in: the resolved scene of a one-rank run stays as it was.
  integer_field(s, "ranks", p, Presence::may(), between(1, max_ranks, true, true), c);
  if (s.contains("ranks") && s["ranks"].is_number_integer() && s["ranks"].get<long long>() > 1 &&
      s["linear"] == "iterative")
    c.fail(child(p, "linear"), "\"iterative\" solves on one rank; with solver.ranks " + shown(s["ranks"]) +
                                   " it must be \"petsc_gamg\", \"direct\" (MUMPS) or \"auto\"");
}

void check_output(json& o, const std::string& p, Checker& c) {
  if (!object_with(o, p, {"every", "interval", "checkpoint_seconds", "checkpoint_every"}, c)) return;
  if (o.contains("interval")) {
    if (o.contains("every"))
      c.fail(child(p, "interval"),
             "cannot be given together with output.every: frames come at times (interval) "
             "or every so many steps (every), not both");
    number_field(o, "interval", p, Presence::must(), above(0), c);
  } else {
    integer_field(o, "every", p, Presence::or_default(1), at_least(1), c);
  }
  number_field(o, "checkpoint_seconds", p, Presence::or_default(60.0), between(0, 1e7, false, true, "0, 1e7"),
               c);
  integer_field(o, "checkpoint_every", p, Presence::may(), at_least(1), c);
}

/// Rules between a contact pair and the time scheme (after both were checked and defaulted), from
/// model::contact_scheme_conflict: what the contact module would refuse at run time is refused here,
/// before a job is queued.
void check_contact_scheme(const json& scene, Checker& c) {
  const json& contact = scene["contact"];
  const json& scheme_name = scene["time"]["scheme"];
  if (!contact.is_array() || !scheme_name.is_string()) return;
  const auto scheme = model::scheme_from_string(scheme_name.get<std::string>());
  if (!scheme) return;
  for (size_t i = 0; i < contact.size(); ++i) {
    if (!contact[i].is_object()) continue;
    const auto enforcement = contact[i].value("enforcement", "") == "penalty" ? model::Enforcement::penalty
                                                                              : model::Enforcement::lagrange;
    const std::string named = contact[i].value("impact", "");
    const auto impact = named == "velocity_correction" ? model::ImpactMode::velocity_correction
                        : named == "exact"             ? model::ImpactMode::exact
                        : named == "located"           ? model::ImpactMode::located
                                                       : model::ImpactMode::persist;
    if (const auto conflict = model::contact_scheme_conflict(*scheme, enforcement, impact))
      c.fail(child(child(child("", "contact"), i), conflict->field), conflict->reason);
  }
}

void check_format(const json& format, const std::string& p, Checker& c) {
  if (format != "stoss-scene/1") c.fail(p, "must be \"stoss-scene/1\", got " + shown(format));
}

}  // namespace

void check_scene(json& scene, Checker& c) {
  const std::initializer_list<std::string_view> fields{"format",   "name",  "bodies", "contact", "gravity",
                                                       "boundary", "loads", "time",   "solver",  "output"};
  if (!object_with(scene, "", fields, c)) return;
  if (const json* format = member(scene, "format", "", Presence::must(), c))
    check_format(*format, "/format", c);
  if (const json* n = member(scene, "name", "", Presence::or_default("unnamed"), c)) string(*n, "/name", c);
  SurfaceIndex index;
  if (json* bodies = member(scene, "bodies", "", Presence::must(), c))
    index = check_bodies(*bodies, "/bodies", c);
  const bool statics = names_static(scene);
  check_entries(
      scene, "contact", index,
      [statics](json& e, const std::string& p, const SurfaceIndex& i, Checker& k) {
        check_contact_pair(e, p, i, statics, k);
      },
      c);
  check_entries(scene, "boundary", index, check_boundary_condition, c);
  check_entries(scene, "loads", index, check_load, c);
  vector3_field(scene, "gravity", "", Presence::or_default(zero3), c);
  if (json* t = member(scene, "time", "", Presence::must(), c)) check_time(*t, "/time", c);
  if (json* s = member(scene, "solver", "", Presence::or_default(json::object()), c))
    check_solver(*s, "/solver", c);
  if (json* o = member(scene, "output", "", Presence::or_default(json::object()), c))
    check_output(*o, "/output", c);
  if (scene.contains("time") && scene["time"].is_object()) check_contact_scheme(scene, c);
  if (statics) check_static_bodies(scene, c);
}

}  // namespace stoss::scene::detail
