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
  std::map<std::string, std::vector<int>> element_sets;     ///< name → element indices (ascending)
  std::map<std::string, std::vector<ElementFace>> surfaces;  ///< name → faces, in outward order via hex_faces

  /// "file:line: element 17" for messages (no line part in binary files).
  std::string where_element(int element) const;
};

/// Reads a Gmsh MSH 4.1 file (ASCII or binary, 8-byte size_t).
/// @note Hexahedra (type 5) become elements, each physical volume an element set; quadrangles (type 3)
///       of a physical surface become faces of that surface (the hexahedron face with the same nodes,
///       oriented outwards from that element). Points and lines are ignored. A physical group without a
///       name is named by its tag. Volume elements of another type, and surface elements other than
///       quadrangles in a physical surface, are errors.
/// @throws MeshFileError naming the file and the line (or byte offset in binary sections).
ImportedMesh read_gmsh(const std::filesystem::path& path, const std::string& shown_name = "");

/// Reads an Abaqus / CalculiX input deck: *NODE, *ELEMENT (TYPE=C3D8 or C3D8R, optional ELSET=),
/// *NSET and *ELSET (ids, set names, GENERATE), *SURFACE (TYPE=ELEMENT: element or ELSET, S1..S6 with the
/// C3D8 face numbering). Other keywords and their data lines are skipped. Names are matched without
/// regard to case (as Abaqus does) and kept as first written.
/// @throws MeshFileError naming the file and the line.
ImportedMesh read_abaqus(const std::filesystem::path& path, const std::string& shown_name = "");

/// read_gmsh for ".msh", read_abaqus for ".inp"; anything else is a MeshFileError.
ImportedMesh read_mesh_file(const std::filesystem::path& path, const std::string& shown_name = "");

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
/// Surface "boundary" (all boundary faces of the body) is added unless the file names one.
/// @throws MeshFileError when the set does not exist or is empty, or the file has no hexahedra.
Selection select_body(const ImportedMesh& mesh, const std::optional<std::string>& element_set,
                      const Transform& transform = {});

}  // namespace stoss::mesh
