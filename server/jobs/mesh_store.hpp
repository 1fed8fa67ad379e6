#pragma once
/// @file The meshes posted to /v1/meshes (docs/api.md, "Meshes"): stored once under DIR/meshes as
/// <sha256 of the bytes>.msh or .inp, content-addressed and never changed, so that a job naming a mesh by
/// id is reproducible from its stored scene. Paths are built only from the hex digest.

#include <filesystem>
#include <string>
#include <string_view>

#include "core/mesh/mesh_file.hpp"

namespace stoss::server::jobs {

/// A stored mesh: its id, format ("msh" | "inp"), the parsed content, and whether this call stored it.
struct StoredMesh {
  std::string id;
  std::string format;
  mesh::ImportedMesh mesh;
  bool created = false;
};

/// "msh" when `bytes` start (after blanks) with $MeshFormat, "inp" when with '*' (a keyword or comment
/// line of a deck); "" when neither.
std::string sniff_mesh_format(std::string_view bytes);

/// Parses `bytes` as a mesh file of `format` ("msh" | "inp") and stores it in `directory` (created when
/// missing): written to a temporary name, synced, renamed to <id>.<format>. Bytes stored before are parsed
/// from the stored file and not written again (created = false).
/// @throws mesh::MeshFileError naming "request body" and the line (or element) when the file is not a
///         usable mesh; std::system_error when the file cannot be written.
StoredMesh store_mesh(const std::filesystem::path& directory, std::string_view bytes, const std::string& format);

}  // namespace stoss::server::jobs
