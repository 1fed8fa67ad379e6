#pragma once
/// @file The one table of the series a run writes (docs/results.md "/series"): each row names a series,
/// its shape, when it is present and how a step fills it. The layout the observers get (and so the HDF5
/// datasets, the partial series file, the JSON and CSV of GET …/series) and every row of values come from
/// it; tests hold docs/results.md, api/openapi.yaml and the page's plots (server/web/stoss.js) to it.
/// Adding a series is adding a row.

#include <span>
#include <string>
#include <vector>

#include "core/model/model.hpp"
#include "core/model/series.hpp"
#include "core/run/measures.hpp"
#include "core/time/step_reduction.hpp"

namespace stoss::run {

/// What one step gives the table: its energies and momenta, its contact report, its Newton solve (null for
/// row 0, the initial state), its wall seconds, its h and the tries the step controller rejected before it
/// (both 0 in row 0).
struct StepMeasures {
  const Balance& balance;
  const ContactRow& contact;
  const time::ReducedStep* newton;
  double seconds;
  double step_size = 0;
  int rejections = 0;
  /// The force each boundary entry exerted on its body in the step (Problem::entry_reactions); null or
  /// empty in row 0, where it is 0.
  const std::vector<Eigen::Vector3d>* reactions = nullptr;
  /// The force each contact pair's master exerted on its slave in the step (MeasuredContact); null or
  /// empty in row 0, where it is 0.
  const std::vector<Eigen::Vector3d>* contact_forces = nullptr;
  /// Each pair's Σ A_I over its slave nodes in contact at the step's end (ContactReport::contact_area);
  /// null or empty: 0.
  const std::vector<double>* contact_areas = nullptr;
};

/// The shape of one row of a series; k (the items) is taken from the scene.
enum class Shape {
  scalar,        ///< [S]
  vector,        ///< [S,3]
  item_vectors,  ///< [S,k,3], one vector per item (a contact pair, a boundary surface, …)
  item_scalars,  ///< [S,k]
};

/// When a series is present, by the effects the scene calls for (docs/results.md, column "present").
enum class Presence {
  always,
  gravity,        ///< a non-zero gravity vector
  contact,        ///< at least one contact pair
  friction,       ///< a pair with friction > 0
  smooth_master,  ///< a pair with a smooth master surface
  loads,     ///< at least one entry in the scene's loads, or a boundary entry with a non-zero displacement
  boundary,  ///< at least one entry in the scene's boundary
};

/// One series: a row of the table.
struct SeriesColumn {
  const char* name;
  Shape shape;
  bool integer;  ///< int32 (counts), else float64
  Presence presence;
  /// How a step fills it: writes the series' values (1, 3, 3k or k) to `values`; `items` is k.
  void (*fill)(const StepMeasures& step, int items, double* values);
  /// k of the item shapes, from the model; null for scalar and vector series.
  int (*items)(const model::Model& model) = nullptr;
};

/// The table, in the order the series are written.
std::span<const SeriesColumn> series_columns();

bool is_present(Presence presence, const model::Model& model);
/// The words of docs/results.md's "present" column: "always", "gravity", "contact", "a frictional pair",
/// "a pair with a smooth master surface", "loads or prescribed motion", "boundary".
std::string presence_text(Presence presence);
/// The type and shape as docs/results.md writes them: "float64 [S]", "int32 [S]", "float64 [S,3]",
/// "float64 [S,k,3]", "float64 [S,k]".
std::string type_text(const SeriesColumn& column);

/// The series of one run: the rows of `columns` present in `model`, their layout and the step rows.
class SeriesRows {
 public:
  explicit SeriesRows(const model::Model& model, std::span<const SeriesColumn> columns = series_columns());
  const model::SeriesLayout& layout() const { return layout_; }
  /// The row of `step` at `time`: every present series filled from `measures`, in layout order.
  model::StepRow row(int step, double time, const StepMeasures& measures) const;

 private:
  std::vector<const SeriesColumn*> present_;  ///< in layout order
  model::SeriesLayout layout_;
};

}  // namespace stoss::run
