#pragma once
/// @file Mesh files written by other tools: Gmsh .msh 4.1 (ASCII and binary) and Abaqus/CalculiX .inp.
/// Both readers produce an ImportedMesh: 8-node hexahedra, named element sets (Gmsh physical volumes,
/// Abaqus *ELSET) and named surfaces as element faces (Gmsh physical surfaces of quadrangles, Abaqus
/// element-based *SURFACE). select_body() cuts one body out of it.

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace stoss::mesh {

/// A mesh file that cannot be used: names the file and where in it (line, or element / byte when
/// there is no line), e.g. "deck.inp:42: element 17: C3D8 needs 8 nodes, got 7".
class MeshFileError : public std::runtime_error {
 public:
  MeshFileError(std::string file, long line, const std::string& message);
  std::string file;
  long line = 0;  ///< 1-based; 0 when the place is not a line (binary files, whole-file problems)
};

/// One face of an element: index into ImportedMesh::hex8 and the local face 0..5 of hex_faces().
struct ElementFace {
  int element = 0;
  int face = 0;
};

/// The content of a mesh file, in file order. Node and element ids are those of the file.
struct ImportedMesh {
  std::string file;  ///< as named by the caller, for messages
  std::vector<Eigen::Vector3d> nodes;
  std::vector<long> node_ids;
  std::vector<Hex> hex8;  ///< indices into nodes, VTK_HEXAHEDRON order (= Gmsh and Abaqus C3D8 order)
  std::vector<long> element_ids;
  std::vector<long> element_lines;  ///< line of each element's definition (0 in binary files)
  std::map<std::string, std::vector<int>> element_sets;      ///< name → element indices (ascending)
  std::map<std::string, std::vector<ElementFace>> surfaces;  ///< name → faces, in outward order via hex_faces
  std::map<std::string, std::vector<int>> node_sets;  ///< name → node indices (ascending): Abaqus *NSET
  /// What the reader left out or turned into something else, one sentence each (e.g. the 2D elements of a
  /// Gmsh export: which became surface faces, how many were skipped).
  std::vector<std::string> notes;
  /// Elements the reader dropped without using them (2D/1D elements not on the hexahedra's boundary): the
  /// scene warns about them (docs/scene.md, "Checks before the run").
  long skipped_elements = 0;

  /// "file:line: element 17" for messages (no line part in binary files).
  std::string where_element(int element) const;
};

/// How much a mesh file may ask of the reader, and which other files it may pull in (docs/api.md "Meshes",
/// docs/scene.md "Meshes from files"). Every count is checked against its total before it is used.
struct ReadLimits {
  /// Nodes, and hexahedra, of the whole file; set members summed over all sets (GENERATE ranges and sets
  /// named in sets expanded) and surface faces summed over all surfaces at most members_per_node × this;
  /// Gmsh element records of every type, entities and physical tags at most records_per_node × this.
  long long max_nodes = 10'000'000;
  /// How messages name max_nodes ("the server limit max_nodes = 200000", the server's --max-nodes).
  std::string limit_name = "the limit of 10000000 nodes per mesh file";
  /// *INCLUDE: refused when false (uploaded decks: a stored mesh is self-contained); when true, only
  /// relative paths without "..", resolved (symbolic links followed) below the top deck's folder, to
  /// regular files, nested at most max_include_depth deep and max_includes in all.
  bool includes = true;
  static constexpr int max_include_depth = 8;
  static constexpr int max_includes = 100;
  static constexpr long long members_per_node = 8;
  static constexpr long long records_per_node = 4;
  /// Longest line (with its keyword continuation lines) of a deck.
  static constexpr std::size_t max_line_bytes = 64 * 1024;

  long long max_members() const { return members_per_node * max_nodes; }
  long long max_records() const { return records_per_node * max_nodes; }
  /// "more than 200000 nodes (the server limit max_nodes = 200000)"; `factor` > 1 for the derived caps:
  /// "more than 1600000 set members in all sets (8 × the server limit max_nodes = 200000)".
  std::string exceeded(const std::string& what, long long factor = 1) const;
};

/// The limits of a mesh posted to the service: no *INCLUDE, the caps from --max-nodes.
ReadLimits upload_limits(long long max_nodes);

/// Reads a Gmsh MSH 4.1 file (ASCII or binary, 8-byte size_t).
/// @note Hexahedra (type 5) become elements, each physical volume an element set; quadrangles (type 3)
///       of a physical surface become faces of that surface (the hexahedron face with the same nodes,
///       oriented outwards from that element). Points and lines are ignored. A physical group without a
///       name is named by its tag. Volume elements of another type, and surface elements other than
///       quadrangles in a physical surface, are errors.
/// @throws MeshFileError naming the file and the line (or byte offset in binary sections).
ImportedMesh read_gmsh(const std::filesystem::path& path, const std::string& shown_name = "",
                       const ReadLimits& limits = {});

/// Reads an Abaqus / CalculiX input deck: *NODE, *ELEMENT (TYPE=C3D8 or C3D8R, optional ELSET=),
/// *NSET and *ELSET (ids, set names, GENERATE), *SURFACE (TYPE=ELEMENT: element or ELSET, S1..S6 with the
/// C3D8 face numbering). Other keywords and their data lines are skipped. Names are matched without
/// regard to case (as Abaqus does) and kept as first written. *INCLUDE as `limits` allow it.
/// @note 2D and 1D elements beside the hexahedra (Gmsh's export writes its physical surfaces as CPS4 and
///       its curves as T3D2): a 4-node quadrilateral whose nodes are those of a boundary face of a
///       hexahedron is that face, and an ELSET holding such elements is a surface of that name (outward
///       order, as *SURFACE); every other 2D or 1D element is skipped. One note says how many of each.
/// @throws MeshFileError naming the file and the line.
ImportedMesh read_abaqus(const std::filesystem::path& path, const std::string& shown_name = "",
                         const ReadLimits& limits = {});

/// read_gmsh for ".msh", read_abaqus for ".inp"; anything else is a MeshFileError. The file must be a
/// regular file (not a device, a FIFO or a directory).
ImportedMesh read_mesh_file(const std::filesystem::path& path, const std::string& shown_name = "",
                            const ReadLimits& limits = {});

/// Parses the bytes of a mesh file of `format` ("msh" | "inp") held in memory, named `shown_name` in
/// messages; no other file is read (an *INCLUDE is refused whatever `limits` say).
ImportedMesh parse_mesh_bytes(std::string_view bytes, const std::string& format,
                              const std::string& shown_name, const ReadLimits& limits);
/// The same for each format.
ImportedMesh parse_gmsh(std::string_view bytes, const std::string& shown_name, const ReadLimits& limits);
ImportedMesh parse_abaqus(std::string_view bytes, const std::string& shown_name, const ReadLimits& limits);

/// The bytes of a mesh file: a regular file, read whole. @throws MeshFileError ("cannot read the file").
std::string read_regular_file(const std::filesystem::path& path, const std::string& shown_name);

/// Similarity transform applied to the nodes of a body: x ↦ translate + R (scale ∘ x), R a rotation by
/// `degrees` about `axis` through the origin.
struct Transform {
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double degrees = 0;
  Eigen::Vector3d translate = Eigen::Vector3d::Zero();
  Eigen::Vector3d apply(const Eigen::Vector3d& x) const;
};

/// One body cut out of an ImportedMesh.
struct Selection {
  BodyMesh body;                            ///< nodes of the selected elements only, renumbered
  std::vector<int> elements;                ///< file element index of each body element
  std::vector<std::string> empty_surfaces;  ///< surfaces of the file with no face on these elements
};

/// The elements of `element_set` (all elements when absent) as a body: its nodes (transformed), and
/// every surface of the file restricted to faces of these elements (empty ones listed, not kept).
/// Surface "boundary" (all boundary faces of the body) is added unless the file names one. Node sets are
/// kept restricted to the body's nodes (a set with none of them is left out).
/// @throws MeshFileError when the set does not exist or is empty, or the file has no hexahedra, or a surface
///         holds faces interior to the body (shared by two of its elements): contact and supports act on
///         a body's boundary, and a support there would silently clamp the inside (docs/scene.md).
Selection select_body(const ImportedMesh& mesh, const std::optional<std::string>& element_set,
                      const Transform& transform = {});

}  // namespace stoss::mesh
