#include "core/mesh/mesh_file.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <fstream>
#include <numbers>
#include <sstream>

namespace stoss::mesh {

namespace {

std::string located(const std::string& file, long line, const std::string& message) {
  return file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + message;
}

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

MeshFileError::MeshFileError(std::string f, long l, const std::string& message)
    : std::runtime_error(located(f, l, message)), file(std::move(f)), line(l) {}

std::string ImportedMesh::where_element(int element) const {
  const long line = element_lines.at(element);
  return located(file, line, "element " + std::to_string(element_ids.at(element)));
}

std::string ReadLimits::exceeded(const std::string& what, long long factor) const {
  return "more than " + std::to_string(factor * max_nodes) + " " + what + " (" +
         (factor == 1 ? "" : std::to_string(factor) + " × ") + limit_name + ")";
}

ReadLimits upload_limits(long long max_nodes) {
  ReadLimits limits;
  limits.max_nodes = max_nodes;
  limits.limit_name = "the server limit max_nodes = " + std::to_string(max_nodes);
  limits.includes = false;
  return limits;
}

std::string read_regular_file(const std::filesystem::path& path, const std::string& shown) {
  std::error_code error;
  // A device (/dev/zero), a FIFO or /proc file never ends or lies about its size: only regular files.
  if (!std::filesystem::exists(path, error)) throw MeshFileError(shown, 0, "cannot read the file");
  if (!std::filesystem::is_regular_file(path, error))
    throw MeshFileError(shown, 0, "cannot read the file (not a regular file)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MeshFileError(shown, 0, "cannot read the file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

ImportedMesh read_mesh_file(const std::filesystem::path& path, const std::string& shown_name,
                            const ReadLimits& limits) {
  const std::string ext = lower_extension(path);
  if (ext == ".msh") return read_gmsh(path, shown_name, limits);
  if (ext == ".inp") return read_abaqus(path, shown_name, limits);
  throw MeshFileError(
      shown_name.empty() ? path.string() : shown_name, 0,
      "unknown mesh file type '" + ext + "' (Stoss reads Gmsh .msh 4.1 and Abaqus/CalculiX .inp)");
}

ImportedMesh parse_mesh_bytes(std::string_view bytes, const std::string& format,
                              const std::string& shown_name, const ReadLimits& limits) {
  if (format == "msh") return parse_gmsh(bytes, shown_name, limits);
  if (format == "inp") return parse_abaqus(bytes, shown_name, limits);
  throw MeshFileError(shown_name, 0, "unknown mesh format '" + format + "' (msh or inp)");
}

Eigen::Vector3d Transform::apply(const Eigen::Vector3d& x) const {
  const double radians = degrees * std::numbers::pi / 180;
  const Eigen::Vector3d scaled = scale.cwiseProduct(x);
  if (degrees == 0 || axis.norm() == 0) return translate + scaled;
  return translate + Eigen::AngleAxisd(radians, axis.normalized()) * scaled;
}

namespace {

/// Throws when a surface of the body holds faces that two of its elements share (docs/scene.md, "Meshes
/// from files"), naming the surface and how many of its faces are interior.
void refuse_interior_faces(const std::string& file, const BodyMesh& body) {
  if (body.surfaces.empty()) return;
  std::map<std::array<int, 4>, int> uses;
  const auto key = [](Quad q) { return std::sort(q.begin(), q.end()), q; };
  for (const Hex& h : body.hex8)
    for (const Quad& q : hex_faces(h)) ++uses[key(q)];
  for (const auto& [name, quads] : body.surfaces) {
    const auto interior =
        std::count_if(quads.begin(), quads.end(), [&](const Quad& q) { return uses[key(q)] > 1; });
    if (interior > 0)
      throw MeshFileError(file, 0,
                          "surface '" + name + "' holds " + std::to_string(interior) + " interior faces of " +
                              std::to_string(quads.size()) +
                              " (faces shared by two elements of the body): contact and supports act on the "
                              "boundary, and a support on them would clamp the inside; name only boundary "
                              "faces (for a whole side, the elements of its outer layer), or use 'boundary'");
  }
}

}  // namespace

namespace {

/// The hexahedra of the named element set (Abaqus names ignore case), or all of them without a name.
std::vector<int> selected_elements(const ImportedMesh& mesh, const std::optional<std::string>& element_set) {
  if (!element_set) {
    std::vector<int> all(mesh.hex8.size());
    for (size_t e = 0; e < mesh.hex8.size(); ++e) all[e] = static_cast<int>(e);
    return all;
  }
  auto it = mesh.element_sets.find(*element_set);
  for (auto other = mesh.element_sets.begin();
       it == mesh.element_sets.end() && other != mesh.element_sets.end(); ++other)
    if (upper(other->first) == upper(*element_set)) it = other;
  if (it == mesh.element_sets.end()) {
    std::string known;
    for (const auto& [name, ignored] : mesh.element_sets) known += (known.empty() ? "" : ", ") + name;
    throw MeshFileError(
        mesh.file, 0,
        "has no element set '" + *element_set + "' (it has " + (known.empty() ? "none" : known) + ")");
  }
  if (it->second.empty()) throw MeshFileError(mesh.file, 0, "element set '" + it->first + "' is empty");
  return it->second;
}

}  // namespace

Selection select_body(const ImportedMesh& mesh, const std::optional<std::string>& element_set,
                      const Transform& transform) {
  if (mesh.hex8.empty()) throw MeshFileError(mesh.file, 0, "has no 8-node hexahedra");
  Selection out;
  out.elements = selected_elements(mesh, element_set);
  std::vector<int> local_node(mesh.nodes.size(), -1);
  std::vector<int> local_element(mesh.hex8.size(), -1);
  for (int e : out.elements)
    for (int n : mesh.hex8[e]) local_node[n] = 0;
  int next = 0;
  for (size_t n = 0; n < mesh.nodes.size(); ++n)
    if (local_node[n] == 0) {
      local_node[n] = next++;
      out.body.nodes.push_back(transform.apply(mesh.nodes[n]));
    }
  for (size_t i = 0; i < out.elements.size(); ++i) {
    const int e = out.elements[i];
    local_element[e] = static_cast<int>(i);
    Hex h;
    for (int k = 0; k < 8; ++k) h[k] = local_node[mesh.hex8[e][k]];
    out.body.hex8.push_back(h);
  }
  for (const auto& [name, faces] : mesh.surfaces) {
    std::vector<Quad> quads;
    for (const ElementFace& f : faces)
      if (local_element[f.element] >= 0)
        quads.push_back(hex_faces(out.body.hex8[local_element[f.element]])[f.face]);
    if (quads.empty())
      out.empty_surfaces.push_back(name);
    else
      out.body.surfaces[name] = std::move(quads);
  }
  refuse_interior_faces(mesh.file, out.body);
  if (mesh.skipped_elements > 0)
    for (const std::string& note : mesh.notes)
      out.body.skipped_note += (out.body.skipped_note.empty() ? mesh.file + ": " : "; ") + note;
  for (const auto& [name, members] : mesh.node_sets) {
    std::vector<int> local;
    for (int n : members)
      if (local_node[n] >= 0) local.push_back(local_node[n]);
    std::sort(local.begin(), local.end());
    if (!local.empty()) out.body.node_sets[name] = std::move(local);
  }
  if (!out.body.surfaces.contains("boundary") &&
      std::find(out.empty_surfaces.begin(), out.empty_surfaces.end(), "boundary") == out.empty_surfaces.end())
    out.body.surfaces["boundary"] = boundary_faces(out.body.hex8);
  return out;
}

}  // namespace stoss::mesh
