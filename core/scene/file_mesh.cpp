#include "core/scene/file_mesh.hpp"

#include <algorithm>
#include <cctype>

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
  if (v && !(v->array() > 0).all())
    c.fail(p, "must be > 0 in every component (no mirroring), got " + shown(scale));
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
    t.scale =
        j["scale"].is_number() ? Eigen::Vector3d::Constant(j["scale"].get<double>()) : vector_of(j["scale"]);
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

/// Which member names the file ("file" or "id") and its text.
struct Source {
  std::string key;
  std::string text;
};

Source source_of(const json& mesh) {
  const std::string key = mesh.contains("id") ? "id" : "file";
  return {key, mesh[key].get<std::string>()};
}

/// The parsed mesh file named by "file" (relative to the scene's directory; *INCLUDE below its folder only)
/// or "id" (a stored mesh: the store's parsed form, or its file, self-contained); nullptr with the reason in
/// `why` when it cannot be had. @throws mesh::MeshFileError when the file is not a usable mesh.
std::shared_ptr<const mesh::ImportedMesh> imported_of(const Source& source, const MeshFiles& where,
                                                      const std::string& label, std::string& why) {
  mesh::ReadLimits limits;
  limits.max_nodes = max_generated_nodes;
  if (source.key == "file") {
    if (where.directory)
      return std::make_shared<const mesh::ImportedMesh>(
          mesh::read_mesh_file(resolved(source.text, *where.directory), label, limits));
    why =
        "mesh files are read only for a scene given as a file (stoss validate|run SCENE.json), relative to "
        "it; through the HTTP API, POST the file to /v1/meshes and name it by \"id\"";
    return nullptr;
  }
  if (!where.stored && !where.parsed) {
    why =
        "mesh ids name meshes stored by the service (POST /v1/meshes); a scene file names its mesh by "
        "\"file\"";
    return nullptr;
  }
  std::shared_ptr<const mesh::ImportedMesh> imported;
  if (where.parsed) {
    imported = where.parsed(source.text);
  } else if (const auto path = where.stored(source.text)) {
    limits.includes = false;  // a stored mesh is self-contained: its id fixes its content
    imported = std::make_shared<const mesh::ImportedMesh>(mesh::read_mesh_file(*path, label, limits));
  }
  if (!imported) why = "no mesh with this id; POST it to /v1/meshes first";
  return imported;
}

/// The name a surface gets in the result file: HDF5 link names hold no '/' and start with no '.' (the
/// rule of link_name in core/output/result_writer.cpp).
std::string result_file_name(std::string name) {
  for (char& c : name)
    if (c == '/') c = '_';
  if (name.empty() || name[0] == '.') name = "_" + name;
  return name;
}

/// Two surfaces of one body that the result file would write under the same name are an issue.
void check_surface_names(const std::map<std::string, std::vector<mesh::Quad>>& surfaces,
                         const std::string& file, const std::string& p, Checker& c) {
  std::map<std::string, std::string> written;
  for (const auto& [name, quads] : surfaces) {
    const auto [it, fresh] = written.try_emplace(result_file_name(name), name);
    if (!fresh)
      c.fail(p, file + ": surfaces '" + it->second + "' and '" + name + "' would both be written as '" +
                    it->first +
                    "' in the result file (names there hold no '/' and start with no '.'); rename one");
  }
}

/// The name a mesh file goes by in messages: the file as written, or "mesh <id>".
std::string label_of(const Source& source) {
  return source.key == "file" ? source.text : "mesh " + source.text;
}

}  // namespace

std::optional<std::set<std::string>> check_file_mesh(json& mesh, const std::string& p,
                                                     const std::optional<std::string>& body_name,
                                                     Checker& c) {
  const size_t start = c.mark();
  const std::string key = mesh.contains("id") ? "id" : "file";
  const std::string fp = child(p, key);
  const auto name = string(mesh[key], fp, c);
  if (name && name->empty()) c.fail(fp, "must not be empty");
  const auto lower_hex = [](unsigned char x) { return std::isdigit(x) || (x >= 'a' && x <= 'f'); };
  if (name && key == "id" && !name->empty() &&
      (name->size() != 64 || !std::all_of(name->begin(), name->end(), lower_hex)))
    c.fail(fp, "must be 64 lowercase hex digits (the id POST /v1/meshes answers), got " + shown(mesh[key]));
  if (const json* e = member(mesh, "elements", p, Presence::may(), c)) {
    const auto elements = string(*e, child(p, "elements"), c);
    if (elements && elements->empty()) c.fail(child(p, "elements"), "must not be empty");
  }
  if (json* t = member(mesh, "transform", p, Presence::may(), c))
    check_transform(*t, child(p, "transform"), c);
  if (c.mark() != start) return std::nullopt;
  const Source source = source_of(mesh);
  const std::string file = label_of(source);
  std::string why;
  mesh::Selection selection;
  std::shared_ptr<const mesh::ImportedMesh> imported;
  try {
    imported = imported_of(source, c.mesh_files, file, why);
    if (!imported) {
      c.fail(fp, why);
      return std::nullopt;
    }
    selection = mesh::select_body(*imported, elements_of(mesh), transform_of(mesh));
  } catch (const mesh::MeshFileError& e) {
    c.fail(fp, e.what());
    return std::nullopt;
  }
  if (selection.body.nodes.size() > static_cast<size_t>(max_generated_nodes))
    c.fail(fp, file + ": more than " + std::to_string(max_generated_nodes) + " nodes");
  int bad = 0;
  for (size_t i = 0; i < selection.body.hex8.size(); ++i) {
    const auto det = unusable_jacobian_determinant(selection.body.nodes, selection.body.hex8[i]);
    if (!det) continue;
    if (++bad <= max_element_issues)
      c.fail(fp, imported->where_element(selection.elements[i]) + ": " + jacobian_problem(*det));
  }
  if (bad > max_element_issues)
    c.fail(fp,
           file + ": " + std::to_string(bad - max_element_issues) + " more inverted or degenerate hexahedra");
  check_surface_names(selection.body.surfaces, file, fp, c);
  if (c.mark() != start) return std::nullopt;
  std::set<std::string> names;
  for (const auto& [name, quads] : selection.body.surfaces) names.insert(name);
  if (body_name)
    for (const auto& [name, nodes] : selection.body.node_sets) c.node_sets[*body_name].insert(name);
  if (body_name)
    for (const std::string& name : selection.empty_surfaces)
      c.surface_notes[*body_name + "/" + name] =
          file + " defines surface '" + name + "', but none of its faces is on " +
          (mesh.contains("elements") ? "an element of '" + mesh["elements"].get<std::string>() + "'"
                                     : "an element");
  return names;
}

mesh::BodyMesh file_body_mesh(const json& mesh, const MeshFiles& mesh_files) {
  const Source source = source_of(mesh);
  std::string why;
  try {
    const auto imported = imported_of(source, mesh_files, label_of(source), why);
    if (!imported) throw SceneError(std::vector<Issue>{{"", why}});
    return mesh::select_body(*imported, elements_of(mesh), transform_of(mesh)).body;
  } catch (const mesh::MeshFileError& e) {
    throw SceneError(std::vector<Issue>{{"", e.what()}});
  }
}

}  // namespace stoss::scene::detail
