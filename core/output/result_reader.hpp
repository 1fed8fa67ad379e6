#pragma once
/// @file Reading a result file (layout: core/output/layout.hpp; formats stoss-result/2 and /1): for tests,
/// `stoss` tools and GET /v1/jobs/{id}/series.

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/model/series.hpp"

namespace stoss::output {

namespace h5 {
class File;
}

/// A result file opened read-only. Missing series or attributes throw std::out_of_range;
/// HDF5 failures throw std::runtime_error naming the file and the object.
class ResultFile {
 public:
  /// Opens result.h5 (or a .partial / .incomplete.h5 file) read-only.
  static ResultFile open(const std::filesystem::path& path);
  ResultFile(ResultFile&&) noexcept;
  ResultFile& operator=(ResultFile&&) noexcept;
  ~ResultFile();

  const std::filesystem::path& path() const;

  /// Names under /series in the order they were written: "time" first, then layout order.
  std::vector<std::string> series_names() const;
  /// /series/<name> as S × components (int32 series converted to double).
  Eigen::MatrixXd series(const std::string& name) const;
  /// Whether /series/<name> is stored as integers.
  bool series_is_integer(const std::string& name) const;
  /// Name, shape and type of /series/<name> ([S], [S,c], [S,k,w], [S,k]; model/series.hpp).
  model::SeriesSpec series_spec(const std::string& name) const;

  /// Root attribute as a string (a string array attribute must hold exactly one element).
  std::string attribute_string(const std::string& name) const;
  /// Root numeric attribute converted to double (complete, step, end, wall_seconds).
  double attribute_double(const std::string& name) const;
  /// Root string array attribute (effects).
  std::vector<std::string> attribute_strings(const std::string& name) const;
  bool has_attribute(const std::string& name) const;

  /// /mesh/nodes: N × 3 reference coordinates.
  Eigen::MatrixXd mesh_nodes() const;
  /// /mesh/hex8: E × 8 node indices.
  Eigen::Matrix<std::int64_t, Eigen::Dynamic, 8> mesh_hex8() const;
  /// Names of the bodies, indexed by /mesh/body.
  std::vector<std::string> body_names() const;
  /// /mesh/body: E body indices.
  Eigen::VectorXi element_bodies() const;
  /// /mesh/node_body: N body indices (format 2).
  Eigen::VectorXi node_bodies() const;
  /// /mesh/surfaces: "body/surface" → F × 4 node indices (format 2; empty for format 1).
  std::map<std::string, Eigen::Matrix<std::int64_t, Eigen::Dynamic, 4>> surfaces() const;

  /// K, the number of frames.
  int frame_count() const;
  /// /frames/time: K values.
  Eigen::VectorXd frame_times() const;
  /// Frame k of /frames/position: N × 3.
  Eigen::MatrixXd frame_positions(int k) const;
  /// Frame k of /frames/velocity: N × 3.
  Eigen::MatrixXd frame_velocities(int k) const;
  /// Frame k's displacement: N × 3 (format 2).
  Eigen::MatrixXd frame_displacements(int k) const;
  /// Whether the frames carry contact_pressure.
  bool has_contact_pressure() const;
  /// Frame k's contact pressure: N values.
  Eigen::VectorXd frame_contact_pressure(int k) const;
  /// Whether the frames carry cauchy_stress and von_mises (format 2, bodies with materials).
  bool has_stress() const;
  /// Frame k's element Cauchy stress: E × 6 (xx, xy, xz, yy, yz, zz).
  Eigen::MatrixXd frame_cauchy_stress(int k) const;
  /// Frame k's element von Mises stress: E values.
  Eigen::VectorXd frame_von_mises(int k) const;

 private:
  explicit ResultFile(std::unique_ptr<h5::File> file);
  bool format_1() const;
  /// Field `name` of frame k as rows of `width`: /frames/<k>/<name> (format 2) or row k of /frames/<name>.
  Eigen::MatrixXd frame_rows(const std::string& name, int k, int width) const;
  std::string series_dataset(const std::string& name) const;

  std::unique_ptr<h5::File> file_;
};

/// Every series of a result as JSON: {"time": [...], "kinetic_energy": [...],
/// "linear_momentum": [[x,y,z], ...], "newton_iterations": [int, ...], ...}; rows as model::row_json.
nlohmann::json series_json(const std::filesystem::path& path);

/// Every series of a result as CSV: a header of names (model::csv_columns: vector series as
/// name_x,name_y,name_z, [S,k,3] as name_<i>_x,…), then one line per step. Numbers round-trip exactly.
std::string series_csv(const std::filesystem::path& path);

}  // namespace stoss::output
