#include "core/scene/file_mesh.hpp"

#include "core/scene/build.hpp"

namespace stoss::scene::detail {

namespace {

namespace fs = std::filesystem;

/// Element issues listed one by one before the rest is summed up.
constexpr int max_element_issues = 10;

Eigen::Vector3d vector_of(const json& v) {
  return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
}

void check_scale(const json& scale, const std::string& p, Checker& c) {
  if (scale.is_number()) {
    number(scale, p, above(0), c);
    return;
  }
  const auto v = vector3(scale, p, c);
  if (v && !(v->array() > 0).all()) c.fail(p, "must be > 0 in every component (no mirroring), got " + shown(scale));
}

void check_transform(json& t, const std::string& p, Checker& c) {
  if (!object_with(t, p, {"translate", "rotate", "scale"}, c)) return;
  vector3_field(t, "translate", p, Presence::may(), c);
  if (json* r = member(t, "rotate", p, Presence::may(), c)) {
    const std::string rp = child(p, "rotate");
    if (object_with(*r, rp, {"axis", "degrees"}, c)) {
      const auto axis = vector3_field(*r, "axis", rp, Presence::must(), c);
      if (axis && axis->norm() == 0) c.fail(child(rp, "axis"), "must not be the zero vector");
      number_field(*r, "degrees", rp, Presence::must(), between(-360, 360, true, true), c);
    }
  }
  if (json* s = member(t, "scale", p, Presence::may(), c)) check_scale(*s, child(p, "scale"), c);
}

mesh::Transform transform_of(const json& mesh) {
  mesh::Transform t;
  if (!mesh.contains("transform")) return t;
  const json& j = mesh["transform"];
  if (j.contains("translate")) t.translate = vector_of(j["translate"]);
  if (j.contains("rotate")) {
    t.axis = vector_of(j["rotate"]["axis"]);
    t.degrees = j["rotate"]["degrees"].get<double>();
  }
  if (j.contains("scale"))
    t.scale = j["scale"].is_number() ? Eigen::Vector3d::Constant(j["scale"].get<double>()) : vector_of(j["scale"]);
  return t;
}

std::optional<std::string> elements_of(const json& mesh) {
  if (!mesh.contains("elements")) return std::nullopt;
  return mesh["elements"].get<std::string>();
}

fs::path resolved(const std::string& file, const fs::path& directory) {
  const fs::path path(file);
  return path.is_absolute() ? path : directory / path;
}

}  // namespace

std::optional<std::set<std::string>> check_file_mesh(json& mesh, const std::string& p,
                                                     const std::optional<std::string>& body_name, Checker& c) {
  const size_t start = c.mark();
  const json* file_value = member(mesh, "file", p, Presence::must(), c);
  const auto file = file_value ? string(*file_value, child(p, "file"), c) : std::nullopt;
  if (file && file->empty()) c.fail(child(p, "file"), "must not be empty");
  if (const json* e = member(mesh, "elements", p, Presence::may(), c)) {
    const auto elements = string(*e, child(p, "elements"), c);
    if (elements && elements->empty()) c.fail(child(p, "elements"), "must not be empty");
  }
  if (json* t = member(mesh, "transform", p, Presence::may(), c)) check_transform(*t, child(p, "transform"), c);
  if (c.mark() != start) return std::nullopt;
  if (!c.mesh_directory) {
    c.fail(child(p, "file"),
           "mesh files are read only for a scene given as a file (stoss validate|run SCENE.json), relative to "
           "it; the HTTP API does not take mesh files yet");
    return std::nullopt;
  }
  mesh::ImportedMesh imported;
  mesh::Selection selection;
  try {
    imported = mesh::read_mesh_file(resolved(*file, *c.mesh_directory), *file);
    selection = mesh::select_body(imported, elements_of(mesh), transform_of(mesh));
  } catch (const mesh::MeshFileError& e) {
    c.fail(child(p, "file"), e.what());
    return std::nullopt;
  }
  if (selection.body.nodes.size() > static_cast<size_t>(max_generated_nodes))
    c.fail(child(p, "file"), *file + ": more than " + std::to_string(max_generated_nodes) + " nodes");
  int bad = 0;
  for (size_t i = 0; i < selection.body.hex8.size(); ++i) {
    const double det = min_jacobian_determinant(selection.body.nodes, selection.body.hex8[i]);
    if (det > 0) continue;
    if (++bad <= max_element_issues)
      c.fail(child(p, "file"), imported.where_element(selection.elements[i]) +
                                   ": inverted or degenerate hexahedron, det J0 = " + rounded_text(det) +
                                   " at a Gauss point (must be > 0; check the node order)");
  }
  if (bad > max_element_issues)
    c.fail(child(p, "file"), *file + ": " + std::to_string(bad - max_element_issues) +
                                 " more inverted or degenerate hexahedra");
  if (c.mark() != start) return std::nullopt;
  std::set<std::string> names;
  for (const auto& [name, quads] : selection.body.surfaces) names.insert(name);
  if (body_name)
    for (const std::string& name : selection.empty_surfaces)
      c.surface_notes[*body_name + "/" + name] =
          *file + " defines surface '" + name + "', but none of its faces is on " +
          (mesh.contains("elements") ? "an element of '" + mesh["elements"].get<std::string>() + "'" : "an element");
  return names;
}

mesh::BodyMesh file_body_mesh(const json& mesh, const std::optional<fs::path>& mesh_directory) {
  const std::string file = mesh["file"].get<std::string>();
  try {
    return mesh::select_body(mesh::read_mesh_file(resolved(file, mesh_directory.value_or(fs::path("."))), file),
                             elements_of(mesh), transform_of(mesh))
        .body;
  } catch (const mesh::MeshFileError& e) {
    throw SceneError(std::vector<Issue>{{"", e.what()}});
  }
}

}  // namespace stoss::scene::detail
