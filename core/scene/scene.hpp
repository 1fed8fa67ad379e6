#pragma once
/// @file Scene JSON → Model: validation with JSON-pointer errors, defaults, mesh building, effect
/// resolution. The contract is api/scene.schema.json (compiled in, see schema()).

#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/mesh/mesh_file.hpp"
#include "core/model/model.hpp"
#include "core/scene/estimates.hpp"

namespace stoss::scene {

/// Largest mesh a generator is asked to build; bigger box/hollow_sphere parameters are an issue
/// (a guard against runaway allocations; the server's own, configurable limits are lower).
inline constexpr long long max_generated_nodes = 10'000'000;

/// Most MPI ranks a scene may ask for (solver.ranks), and the bound of the service's rank flags.
inline constexpr int max_ranks = 4096;

/// One problem with a scene: where (RFC 6901 JSON pointer, "" = the whole document) and which rule
/// it breaks, with the offending value, e.g. {"/bodies/1/material/poisson_ratio",
/// "must be in (-1, 0.5), got 0.5"}.
struct Issue {
  std::string pointer;
  std::string message;
};

/// Something in a valid scene that looks like a mistake (docs/scene.md, "Checks before the run"): a stable
/// `code` ("contact_behind_master", "density_unit", …), where (JSON pointer) and what to do about it. An
/// expert may mean it, so it never stops a run.
struct Warning {
  std::string code;
  std::string pointer;
  std::string message;
};

/// A choice the scene left open and loading made (today: each pair's master_surface and switch_gap), and why.
struct ResolvedChoice {
  std::string pointer;  ///< e.g. "/contact/0/master_surface"
  std::string value;    ///< "smooth", "faceted", "keep", "clamp"
  std::string reason;
};

/// A scene that cannot be run: every issue found, not just the first.
/// @note what() lists them one per line as "pointer: message" (just "message" for pointer "").
class SceneError : public std::runtime_error {
 public:
  explicit SceneError(std::vector<Issue> issues);
  std::vector<Issue> issues;
};

/// Where the mesh files a scene names are read (docs/scene.md, "Meshes from files").
struct MeshFiles {
  /// "mesh": {"file": ...} is read relative to this directory (the scene file's); without one a scene
  /// naming a mesh file is invalid.
  std::optional<std::filesystem::path> directory;
  /// "mesh": {"id": ...}: the stored file of a mesh id (.msh or .inp), nullopt when no mesh has the id;
  /// unset, a scene naming a mesh id is invalid. The server's is its store of POST /v1/meshes.
  std::function<std::optional<std::filesystem::path>(const std::string& id)> stored;
  /// "mesh": {"id": ...}, when set (the server's): the parsed content of the stored mesh, shared by every
  /// request that names it (parsed once), nullptr when no mesh has the id; may throw mesh::MeshFileError.
  /// Unset, the file `stored` names is read.
  std::function<std::shared_ptr<const mesh::ImportedMesh>(const std::string& id)> parsed;
};

/// Validates a scene, fills in defaults, builds the mesh (bodies in order) and resolves effects.
/// @note model.scene is the input with every default filled in; model.effects = resolve_effects.
/// @note Mesh files ("mesh": {"file": ...}) are read relative to `mesh_directory`; without one (scenes
///       posted to the HTTP API) a scene naming a mesh file is invalid.
/// @throws SceneError listing every issue found.
model::Model load(const nlohmann::json& scene,
                  const std::optional<std::filesystem::path>& mesh_directory = std::nullopt);
/// load() with mesh files from `mesh_files` (a directory for "file", a store for "id").
model::Model load(const nlohmann::json& scene, const MeshFiles& mesh_files);

/// The model of a scene that load() already resolved (its model.scene): built without validating it
/// again, the worker's path for a job whose scene the server validated and resolved once, at POST.
/// A scene without the defaults load() fills in (a job queued by an older server) goes through load().
/// @throws what building the mesh throws (a stored mesh file that vanished).
model::Model load_resolved(const nlohmann::json& resolved, const MeshFiles& mesh_files);

/// load() of a file, mesh files relative to the file's directory. An unreadable file or malformed
/// JSON is a SceneError with pointer "" and the reason (for JSON: the parser's message with line and
/// column).
model::Model load_file(const std::string& path);

/// What a dry run reports (POST /v1/validate, `stoss validate`).
struct Summary {
  std::vector<std::string> effects;
  int nodes = 0;
  int elements = 0;
  int dofs = 0;
  int steps = 0;   ///< the time steps; with time.tolerance at most end/min_step (model::step_bound)
  int frames = 0;  ///< frames written: step 0, every output.every-th step (or each output.interval), the last
  int ranks = 1;   ///< solver.ranks: the MPI ranks the run asks for
  std::vector<Warning> warnings;        ///< scene::warnings (warnings.hpp)
  std::vector<ResolvedChoice> choices;  ///< scene::resolved_choices
  Estimates estimates;                  ///< scales and the run-time estimate (estimates.hpp)
};
Summary summarize(const model::Model& model);

/// The scene JSON Schema (api/scene.schema.json, draft 2020-12), parsed.
nlohmann::json schema();

}  // namespace stoss::scene
