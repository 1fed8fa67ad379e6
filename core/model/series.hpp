#pragma once
/// @file The shape of the series a run reports (docs/results.md "/series"): the layout the observers get,
/// and the two text forms every route uses, CSV columns and JSON rows, so that the HDF5 file, GET …/series
/// (JSON and CSV, complete and partial) and the page agree on one rule. Which series a run has and how a
/// step fills them is the table in core/run/series_table.hpp.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace stoss::model {

/// One named time series (docs/results.md /series/<name>): `components` values per step, stored as
///   [S]       items = 0, components = 1
///   [S,c]     items = 0, components = c (3 for vectors)
///   [S,k,w]   items = k, components = k·w (w = 3: one vector per item, e.g. per contact pair)
///   [S,k]     items = k, components = k
struct SeriesSpec {
  std::string name;
  int components = 1;
  bool integer = false;  ///< stored as int32
  int items = 0;         ///< k of [S,k,…], taken from the scene; 0: no item axis

  /// The shape of one row, the dataset's shape without S: {}, {c}, {k, w} or {k}.
  std::vector<int> row_shape() const;
  /// The spec of a stored dataset of row shape `shape` ({}, {c}, {k}, {k, w}); {k} reads back as {c}.
  static SeriesSpec of_shape(std::string name, const std::vector<int>& shape, bool integer);
};

/// CSV header cells of a series (docs/results.md "Reading a result"): name; name_x,name_y,name_z for [S,3];
/// name_<i>_x,name_<i>_y,name_<i>_z for [S,k,3]; name_<i> for [S,k] and other widths [S,c]; name_<i>_<j>
/// for [S,k,w] with w ≠ 3.
std::vector<std::string> csv_columns(const SeriesSpec& spec);

/// One row of a series as JSON: a number for [S], [x, y, z] (or c numbers) for [S,c], k such arrays for
/// [S,k,w], k numbers for [S,k]; int32 series as integers, non-finite values as null.
nlohmann::json row_json(const SeriesSpec& spec, const double* values);

/// The series a run writes; only those of effects the scene calls for (docs/results.md).
struct SeriesLayout {
  std::vector<SeriesSpec> series;
  int index_of(const std::string& name) const;  ///< first value of the series in a row, -1 if absent
  int row_size() const;                         ///< sum of components
};

}  // namespace stoss::model
