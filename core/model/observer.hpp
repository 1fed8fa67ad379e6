#pragma once
/// @file What a run reports while it goes: the series layout, each converged step, frames, the summary.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/model/model.hpp"
#include "core/model/series.hpp"

namespace stoss::model {

/// Values of every series at one converged step (t0 included as step 0), in layout order.
struct StepRow {
  int step = 0;
  double time = 0;
  std::vector<double> values;  ///< row_size() values, components of a series contiguous
};

/// Node and element fields written as a frame (docs/results.md /frames).
struct Frame {
  double time = 0;
  Eigen::VectorXd position;          ///< 3 per node
  Eigen::VectorXd velocity;          ///< 3 per node
  Eigen::VectorXd contact_pressure;  ///< 1 per node; empty when the scene has no contact
  Eigen::VectorXd cauchy_stress;     ///< 6 per element (xx, xy, xz, yy, yz, zz); empty: no stresses
  Eigen::VectorXd von_mises;         ///< 1 per element, of cauchy_stress; empty with it
};

/// One named check of a finished run against its bound (docs/results.md, "Verdict").
struct Check {
  std::string name;
  double value = 0;
  double bound = 0;
  bool passed = true;
};

/// What a finished (or stopped) run reports: the job summary of docs/api.md.
struct Summary {
  bool completed = false;     ///< false when canceled or failed
  int steps = 0;              ///< converged steps
  int resumed_from_step = 0;  ///< the checkpoint's step when the run went on from one (0: from the start)
  double end_time = 0;
  double initial_energy = 0;
  /// max over steps |H_n − W_n − H_0| / |H_0|, W_n the loads' external work; with loads the scale is
  /// max_{k≤n} |H_k|, meaningful for a loaded body that starts at rest (H_0 = 0).
  double energy_drift = 0;
  double external_work = 0;           ///< W at the end: the loads' work since t_0 (series/external_work)
  double linear_momentum_drift = 0;   ///< max |L_n − L_0| / max(|L_0|, m·v scale)
  double angular_momentum_drift = 0;  ///< max |J_n − J_0| / max(|J_0|, ...)
  double max_penetration = 0;  ///< only meaningful with contact: series max_penetration, max over steps
  double max_own_face_penetration = 0;  ///< with contact: active slave nodes below their own master face
  double max_faceted_penetration = 0;   ///< with a smooth master: the same nodes against the mesh's faces
  int newton_iterations = 0;            ///< total
  double newton_iterations_per_step = 0;
  double wall_seconds = 0;
  /// Where wall_seconds went (each ≤ it; the rest is Newton's own vector work, the velocity
  /// correction and the like). Assembly: the model's setup (geometry, mass), the inertia rows, the
  /// elasticity and gravity terms, the Jacobian pattern. Contact: everything the contact terms do
  /// (setup, search, residual and Jacobian rows, active sets). Linear solver: analysis,
  /// factorisations and solves. Output: energies and momenta per step, frames, the observer's calls.
  double assembly_seconds = 0;
  double contact_seconds = 0;
  double linear_solver_seconds = 0;
  /// linear_solver_seconds split: analysis and factorisations (petsc_gamg: preconditioner setups), solves.
  double linear_factorization_seconds = 0, linear_solve_seconds = 0;
  double output_seconds = 0;
  /// Peak resident set of the process running the job (its VmHWM, run/timing.hpp), at the end of the run.
  double peak_memory_bytes = 0;
  /// With an iterative linear solver (solver.linear iterative or petsc_gamg): Krylov iterations per linear
  /// solve, and the solves that did not converge and fell back to LU. 0 with the direct solver.
  double krylov_iterations_per_solve = 0;
  int krylov_fallbacks = 0;
  /// What the checks of the run measure (run/checks.hpp, docs/results.md "Verdict"): with E_n = H_n + D_n
  /// − W_n − Σ contact_energy_jump, the largest |E_n − E_0| and E_n − E_0, the largest |H_n|, Σ jumps so far,
  /// and the steps that needed a step reduction.
  double energy_balance_error = 0, energy_balance_rise = 0, max_abs_energy = 0, contact_energy_jumps = 0;
  /// Where the system is not free: the largest |Δp_n − J_n| over the steps, J_n the step's external impulse
  /// (loads, gravity, supports), relative to the momenta's and the impulses' magnitudes (docs/results.md
  /// (V10)).
  double impulse_balance_error = 0;
  int reduced_steps = 0;
  std::vector<Check> checks;  ///< filled when the run ends
  std::string verdict;        ///< "ok" or "suspect" (a check failed); empty until the run ends
};

/// Whether the run checked `name` (the momenta are checked only where the system is free, run/checks.hpp).
inline bool has_check(const Summary& s, const std::string& name) {
  for (const Check& c : s.checks)
    if (c.name == name) return true;
  return false;
}

/// The checks as JSON: [{name, value, bound, passed}] (the job JSON's `checks`, result.h5's `checks`).
inline nlohmann::json checks_json(const std::vector<Check>& checks) {
  nlohmann::json out = nlohmann::json::array();
  for (const Check& c : checks)
    out.push_back({{"name", c.name}, {"value", c.value}, {"bound", c.bound}, {"passed", c.passed}});
  return out;
}

/// Receives a run as it happens. The HDF5 writer is one observer, a job's progress another.
class Observer {
 public:
  virtual ~Observer() = default;
  /// Called once before step 1, with the series layout and the node count.
  virtual void begin(const Model& model, const SeriesLayout& layout) {}
  /// Every converged step, and step 0 (the initial state).
  virtual void step(const StepRow& row) {}
  /// Frames at step 0, every output.every steps, and the last step.
  virtual void frame(const Frame& frame) {}
  /// A log line (solver events, warnings). Not for progress.
  virtual void log(const std::string& line) {}
  /// The run goes on from a checkpoint at `step`: the rows and frames up to it came back at once, the
  /// steps after it are computed now (a rate or an ETA counts from here).
  virtual void resumed(int step) {}
  /// Called once at the end, whether the run completed, was canceled or failed.
  virtual void end(const Summary& summary) {}
};

/// Fans one run out to several observers.
class ObserverList : public Observer {
 public:
  explicit ObserverList(std::vector<Observer*> observers) : observers_(std::move(observers)) {}
  void begin(const Model& m, const SeriesLayout& l) override {
    for (auto* o : observers_) o->begin(m, l);
  }
  void step(const StepRow& r) override {
    for (auto* o : observers_) o->step(r);
  }
  void frame(const Frame& f) override {
    for (auto* o : observers_) o->frame(f);
  }
  void log(const std::string& s) override {
    for (auto* o : observers_) o->log(s);
  }
  void resumed(int step) override {
    for (auto* o : observers_) o->resumed(step);
  }
  void end(const Summary& s) override {
    for (auto* o : observers_) o->end(s);
  }

 private:
  std::vector<Observer*> observers_;
};

}  // namespace stoss::model
