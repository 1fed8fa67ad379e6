#include "core/run/series_table.hpp"

#include <algorithm>
#include <stdexcept>

namespace stoss::run {

namespace {

using S = const StepMeasures&;

void put3(const Eigen::Vector3d& v, double* out) {
  for (int k = 0; k < 3; ++k) out[k] = v[k];
}

/// k vectors of `items` at `out`, 0 where `items` is null or empty (row 0).
void put_items(const std::vector<Eigen::Vector3d>* items, int k, double* out) {
  for (int e = 0; e < k; ++e)
    put3(items && !items->empty() ? (*items)[size_t(e)] : Eigen::Vector3d::Zero(), out + 3 * e);
}

int boundary_entries(const model::Model& m) {
  return int(m.boundary.size());
}
int contact_pairs(const model::Model& m) {
  return int(m.contact.size());
}

// One row per series (docs/results.md "/series" gives their meaning).
const SeriesColumn table[] = {
    {"kinetic_energy", Shape::scalar, false, Presence::always,
     [](S s, int, double* v) { v[0] = s.balance.kinetic; }},
    {"strain_energy", Shape::scalar, false, Presence::always,
     [](S s, int, double* v) { v[0] = s.balance.strain; }},
    {"potential_energy", Shape::scalar, false, Presence::gravity,
     [](S s, int, double* v) { v[0] = s.balance.potential; }},
    {"total_energy", Shape::scalar, false, Presence::always,
     [](S s, int, double* v) { v[0] = s.balance.total(); }},
    {"dissipated_energy", Shape::scalar, false, Presence::friction,  // §5.2 item 7
     [](S s, int, double* v) { v[0] = s.balance.dissipated; }},
    {"external_work", Shape::scalar, false,
     Presence::loads,  // (5b.5), (5b.11): loads' and supports' work since t_0
     [](S s, int, double* v) { v[0] = s.balance.external_work; }},
    {"reaction_force", Shape::item_vectors, false,
     Presence::boundary,  // (5b.10): per boundary entry, row 0 is 0
     [](S s, int k, double* v) { put_items(s.reactions, k, v); }, boundary_entries},
    {"linear_momentum", Shape::vector, false, Presence::always,
     [](S s, int, double* v) { put3(s.balance.linear, v); }},
    {"angular_momentum", Shape::vector, false, Presence::always,
     [](S s, int, double* v) { put3(s.balance.angular, v); }},
    {"active_contacts", Shape::scalar, true, Presence::contact,
     [](S s, int, double* v) { v[0] = s.contact.active; }},
    {"max_penetration", Shape::scalar, false, Presence::contact,
     [](S s, int, double* v) { v[0] = s.contact.max_penetration; }},
    {"contact_energy_jump", Shape::scalar, false, Presence::contact,
     [](S s, int, double* v) { v[0] = s.contact.energy_jump; }},
    {"face_switches", Shape::scalar, true, Presence::contact,
     [](S s, int, double* v) { v[0] = s.contact.switches; }},
    {"unprojected_nodes", Shape::scalar, true, Presence::contact,  // near slave nodes no face accepts (§3.4)
     [](S s, int, double* v) { v[0] = s.contact.unprojected; }},
    {"max_faceted_penetration", Shape::scalar, false, Presence::smooth_master,
     [](S s, int, double* v) { v[0] = s.contact.faceted_penetration; }},
    {"slipping_contacts", Shape::scalar, true, Presence::friction,
     [](S s, int, double* v) { v[0] = s.contact.slipping; }},
    {"contact_force", Shape::item_vectors, false, Presence::contact,  // (5b.12): per pair, row 0 is 0
     [](S s, int k, double* v) { put_items(s.contact_forces, k, v); }, contact_pairs},
    {"contact_area", Shape::item_scalars, false, Presence::contact,  // Σ A_I of the slave nodes in contact
     [](S s, int k, double* v) {
       for (int e = 0; e < k; ++e)
         v[e] = s.contact_areas && !s.contact_areas->empty() ? (*s.contact_areas)[size_t(e)] : 0.0;
     },
     contact_pairs},
    {"newton_iterations", Shape::scalar, true, Presence::always,
     [](S s, int, double* v) { v[0] = s.newton ? s.newton->iterations : 0; }},
    {"residual_norm", Shape::scalar, false, Presence::always,
     [](S s, int, double* v) { v[0] = s.newton ? s.newton->residuals.back() : 0.0; }},
    {"step_seconds", Shape::scalar, false, Presence::always, [](S s, int, double* v) { v[0] = s.seconds; }},
    {"substeps", Shape::scalar, true, Presence::always,  // automatic step reduction: 1, or the substeps taken
     [](S s, int, double* v) { v[0] = s.newton ? s.newton->substeps : 1; }},
    {"step_size", Shape::scalar, false, Presence::always,  // h of the step: time.step, or the controller's
     [](S s, int, double* v) { v[0] = s.step_size; }},
    {"rejected_steps", Shape::scalar, true, Presence::always,  // tries the step controller rejected (§2.7)
     [](S s, int, double* v) { v[0] = s.rejections; }},
};

bool any_smooth_master(const model::Model& m) {
  return std::any_of(m.contact.begin(), m.contact.end(), [](const model::ContactPair& p) {
    return p.master_surface == model::MasterSurface::smooth;
  });
}

model::SeriesSpec spec_of(const SeriesColumn& column, const model::Model& model) {
  const int items = column.items ? column.items(model) : 0;
  if ((column.shape == Shape::item_vectors || column.shape == Shape::item_scalars) !=
      (column.items != nullptr))
    throw std::logic_error(std::string("series ") + column.name +
                           ": items are given exactly for the item shapes");
  switch (column.shape) {
    case Shape::scalar:
      return {column.name, 1, column.integer, 0};
    case Shape::vector:
      return {column.name, 3, column.integer, 0};
    case Shape::item_vectors:
      return {column.name, 3 * items, column.integer, items};
    case Shape::item_scalars:
      return {column.name, items, column.integer, items};
  }
  throw std::logic_error("unknown series shape");
}

}  // namespace

std::span<const SeriesColumn> series_columns() {
  return table;
}

bool is_present(Presence presence, const model::Model& m) {
  switch (presence) {
    case Presence::always:
      return true;
    case Presence::gravity:
      return m.has_effect(model::effect::gravity);
    case Presence::contact:
      return !m.contact.empty();
    case Presence::friction:
      return m.has_effect(model::effect::contact_frictional);
    case Presence::smooth_master:
      return any_smooth_master(m);
    case Presence::loads:
      return m.has_external_work();
    case Presence::boundary:
      return !m.boundary.empty();
  }
  return false;
}

std::string presence_text(Presence presence) {
  switch (presence) {
    case Presence::always:
      return "always";
    case Presence::gravity:
      return "gravity";
    case Presence::contact:
      return "contact";
    case Presence::friction:
      return "a frictional pair";
    case Presence::smooth_master:
      return "a pair with a smooth master surface";
    case Presence::loads:
      return "loads or prescribed motion";
    case Presence::boundary:
      return "boundary";
  }
  return "";
}

std::string type_text(const SeriesColumn& column) {
  const char* shape = column.shape == Shape::scalar         ? "[S]"
                      : column.shape == Shape::vector       ? "[S,3]"
                      : column.shape == Shape::item_vectors ? "[S,k,3]"
                                                            : "[S,k]";
  return std::string(column.integer ? "int32 " : "float64 ") + shape;
}

SeriesRows::SeriesRows(const model::Model& model, std::span<const SeriesColumn> columns) {
  for (const SeriesColumn& column : columns)
    if (is_present(column.presence, model)) {
      present_.push_back(&column);
      layout_.series.push_back(spec_of(column, model));
    }
}

model::StepRow SeriesRows::row(int step, double time, const StepMeasures& measures) const {
  model::StepRow row{step, time, std::vector<double>(static_cast<size_t>(layout_.row_size()))};
  double* values = row.values.data();
  for (size_t k = 0; k < present_.size(); ++k) {
    present_[k]->fill(measures, layout_.series[k].items, values);
    values += layout_.series[k].components;
  }
  return row;
}

}  // namespace stoss::run
