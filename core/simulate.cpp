#include "core/simulate.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <cstdlib>
#include <sstream>

#include <sys/resource.h>

#include "core/contact/contact.hpp"
#include "core/fem/assembly.hpp"
#include "core/output/checkpoint.hpp"
#include "core/time/integrator.hpp"
#include "core/time/step_reduction.hpp"

namespace stoss {
namespace {

using model::Model;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Peak resident set of this process so far (getrusage ru_maxrss, kB on Linux), in bytes.
double peak_resident_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return double(usage.ru_maxrss) * 1024.0;
}

/// Everything a run builds from the model: only the terms the scene calls for.
struct Problem {
  std::vector<fem::ElementGeometry> geometry;
  solve::SparseMatrix mass;
  std::unique_ptr<fem::ElasticityTerm> elasticity;
  std::unique_ptr<fem::GravityTerm> gravity;
  std::vector<std::unique_ptr<contact::ContactTerm>> contact;  ///< one per pair; none without contact
  std::vector<char> fixed;
  double total_mass = 0;
  double length_scale = 1;
  double setup_contact_seconds = 0;  ///< building the contact terms
  double setup_seconds = 0;          ///< the rest of build_problem: geometry, mass, elasticity
};

double bounding_box_diagonal(const mesh::Mesh& mesh) {
  Eigen::Vector3d lo = mesh.nodes.front(), hi = mesh.nodes.front();
  for (const auto& p : mesh.nodes) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return std::max((hi - lo).norm(), 1e-300);
}

std::vector<char> fixed_dofs(const Model& m) {
  std::vector<char> fixed(m.dof_count(), 0);
  for (const model::Boundary& b : m.boundary)
    for (int node : m.mesh.surface_nodes(b.surface))
      for (int k = 0; k < 3; ++k)
        if (b.fix[k]) fixed[3 * node + k] = 1;
  return fixed;
}

Problem build_problem(const Model& m) {
  const auto t0 = Clock::now();
  Problem p;
  for (const model::ContactPair& pair : m.contact)
    p.contact.push_back(contact::make_pair_term(m, pair));
  if (!m.contact.empty()) p.setup_contact_seconds = seconds_since(t0);
  const auto t1 = Clock::now();
  p.geometry = fem::precompute_mesh(m.mesh);
  std::vector<double> density;
  std::vector<std::shared_ptr<const fem::Material>> body_material, material;
  for (const model::BodySpec& body : m.bodies) body_material.push_back(fem::make_material(body.material));
  for (int body : m.mesh.element_body) {
    density.push_back(m.bodies[body].material.density);
    material.push_back(body_material[body]);
  }
  p.mass = contact::contact_mass(m, fem::assemble_mass(m.mesh, p.geometry, density));  // theory.md §4.6.1
  p.elasticity = std::make_unique<fem::ElasticityTerm>(m.mesh, p.geometry, std::move(material));
  if (m.has_effect(model::effect::gravity))
    p.gravity = std::make_unique<fem::GravityTerm>(p.mass, *m.gravity);
  p.fixed = fixed_dofs(m);
  p.total_mass = p.mass.sum() / 3;
  p.length_scale = bounding_box_diagonal(m.mesh);
  p.setup_seconds = seconds_since(t1);
  return p;
}

/// v_I = v_0 + ω × (X_I − c), c the given centre or the body's centre of mass; zero on fixed dofs.
Eigen::VectorXd initial_velocity(const Model& m, const Problem& p, const Eigen::VectorXd& X) {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(X.size());
  const Eigen::VectorXd nodal_mass = p.mass * Eigen::VectorXd::Ones(X.size());
  for (size_t b = 0; b < m.bodies.size(); ++b) {
    const mesh::Body& body = m.mesh.bodies[b];
    const model::BodySpec& spec = m.bodies[b];
    Eigen::Vector3d com = Eigen::Vector3d::Zero();
    double mass = 0;
    for (int I = body.node_begin; I < body.node_end; ++I) {
      com += nodal_mass[3 * I] * X.segment<3>(3 * I);
      mass += nodal_mass[3 * I];
    }
    const Eigen::Vector3d center = spec.center.value_or(com / mass);
    for (int I = body.node_begin; I < body.node_end; ++I)
      v.segment<3>(3 * I) =
          spec.initial_velocity + spec.initial_angular_velocity.cross(X.segment<3>(3 * I) - center);
  }
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (p.fixed[i]) v[i] = 0;
  return v;
}

bool any_smooth_master(const Model& m) {
  return std::any_of(m.contact.begin(), m.contact.end(),
                     [](const model::ContactPair& p) { return p.master_surface == model::MasterSurface::smooth; });
}

model::SeriesLayout series_layout(const Model& m) {
  model::SeriesLayout l;
  l.series = {{"kinetic_energy"}, {"strain_energy"}};
  if (m.has_effect(model::effect::gravity)) l.series.push_back({"potential_energy"});
  l.series.push_back({"total_energy"});
  if (m.has_effect(model::effect::contact_frictional))
    l.series.push_back({"dissipated_energy"});  // §5.2 item 7
  l.series.push_back({"linear_momentum", 3});
  l.series.push_back({"angular_momentum", 3});
  if (!m.contact.empty()) {
    l.series.push_back({"active_contacts", 1, true});
    l.series.push_back({"max_penetration"});
    l.series.push_back({"contact_energy_jump"});
    l.series.push_back({"face_switches", 1, true});
    l.series.push_back({"unprojected_nodes", 1, true});  // near slave nodes no face accepts (§3.4)
    if (any_smooth_master(m)) l.series.push_back({"max_faceted_penetration"});
    if (m.has_effect(model::effect::contact_frictional)) l.series.push_back({"slipping_contacts", 1, true});
  }
  l.series.push_back({"newton_iterations", 1, true});
  l.series.push_back({"residual_norm"});
  l.series.push_back({"step_seconds"});
  l.series.push_back({"substeps", 1, true});  // automatic step reduction: 1, or the substeps taken
  return l;
}

/// Energies and momenta (1.10)–(1.11) of a state; `contact` is the penalty energy Σ W_N + W_T (5.1),
/// `dissipated` the Coulomb work D so far (§5.2 item 7).
struct Balance {
  double kinetic = 0, strain = 0, potential = 0, contact = 0, dissipated = 0;
  Eigen::Vector3d linear = Eigen::Vector3d::Zero(), angular = Eigen::Vector3d::Zero();
  double momentum_scale = 0, angular_scale = 0;  ///< Σ|p_I|, Σ|x_I||p_I|: scales for relative drifts
  double total() const { return kinetic + strain + potential + contact; }  // H of (5.4)
};

/// The contact series of one step (docs/results.md), summed or maximised over the pairs.
struct ContactRow {
  int active = 0, slipping = 0, switches = 0, unprojected = 0;
  double max_penetration = 0, own_face_penetration = 0, faceted_penetration = 0, energy_jump = 0;
};

/// Folds the contact row of one substep into the step's: the last active count, the worst
/// penetrations, the sum of the jumps.
void add_substep(ContactRow& step, const ContactRow& sub) {
  step.active = sub.active;
  step.max_penetration = std::max(step.max_penetration, sub.max_penetration);
  step.own_face_penetration = std::max(step.own_face_penetration, sub.own_face_penetration);
  step.faceted_penetration = std::max(step.faceted_penetration, sub.faceted_penetration);
  step.energy_jump += sub.energy_jump;
  step.switches += sub.switches;
  step.unprojected = std::max(step.unprojected, sub.unprojected);
  step.slipping += sub.slipping;
}

ContactRow contact_row(const Problem& p, const time::Integrator* integrator) {
  ContactRow c;
  for (const auto& term : p.contact) {
    const contact::ContactReport& r = term->report();
    c.active += r.active;
    c.max_penetration = std::max(c.max_penetration, r.max_penetration);
    c.own_face_penetration = std::max(c.own_face_penetration, r.max_own_face_penetration);
    c.faceted_penetration = std::max(c.faceted_penetration, r.max_faceted_penetration);
    c.energy_jump += r.energy_jump;
    c.switches += r.switches;
    c.unprojected += r.unassigned;
    c.slipping += r.slipping;
  }
  // The velocity correction (4.12) restores (part of) the activation jump as kinetic energy.
  if (integrator) c.energy_jump += integrator->velocity_correction_energy();
  return c;
}

Balance balance(const Problem& p, const time::State& s) {
  Balance b;
  const Eigen::VectorXd momentum = p.mass * s.v;
  b.kinetic = 0.5 * s.v.dot(momentum);
  b.strain = p.elasticity->energy(s.x);
  if (p.gravity) b.potential = p.gravity->energy(s.x);
  for (const auto& term : p.contact) {
    b.contact += term->energy(s.x);
    b.dissipated += term->dissipated_energy();
  }
  for (Eigen::Index I = 0; I < s.x.size() / 3; ++I) {
    const Eigen::Vector3d pI = momentum.segment<3>(3 * I), xI = s.x.segment<3>(3 * I);
    b.linear += pI;
    b.angular += xI.cross(pI);
    b.momentum_scale += pI.norm();
    b.angular_scale += xI.norm() * pI.norm();
  }
  return b;
}

model::StepRow step_row(const time::State& s, const Balance& b, const ContactRow& c,
                        const model::SeriesLayout& layout, const time::ReducedStep* newton,
                        double step_seconds) {
  model::StepRow row{s.step, s.t, {}};
  row.values.push_back(b.kinetic);
  row.values.push_back(b.strain);
  if (layout.index_of("potential_energy") >= 0) row.values.push_back(b.potential);
  row.values.push_back(b.total());
  if (layout.index_of("dissipated_energy") >= 0) row.values.push_back(b.dissipated);
  for (int k = 0; k < 3; ++k) row.values.push_back(b.linear[k]);
  for (int k = 0; k < 3; ++k) row.values.push_back(b.angular[k]);
  if (layout.index_of("active_contacts") >= 0) {
    row.values.push_back(c.active);
    row.values.push_back(c.max_penetration);
    row.values.push_back(c.energy_jump);
    row.values.push_back(c.switches);
    row.values.push_back(c.unprojected);
    if (layout.index_of("max_faceted_penetration") >= 0) row.values.push_back(c.faceted_penetration);
    if (layout.index_of("slipping_contacts") >= 0) row.values.push_back(c.slipping);
  }
  row.values.push_back(newton ? newton->iterations : 0);
  row.values.push_back(newton ? newton->residuals.back() : 0.0);
  row.values.push_back(step_seconds);
  row.values.push_back(newton ? newton->substeps : 1);
  return row;
}

/// Tracks the drifts of the summary against the initial state.
void update_drifts(model::Summary& sum, const Balance& b0, const Balance& b) {
  const double H0 = std::abs(b0.total()) > 0 ? std::abs(b0.total()) : 1.0;
  sum.energy_drift = std::max(sum.energy_drift, std::abs(b.total() - b0.total()) / H0);
  const double Ls = std::max(b0.linear.norm(), b0.momentum_scale),
               Js = std::max(b0.angular.norm(), b0.angular_scale);
  if (Ls > 0)
    sum.linear_momentum_drift = std::max(sum.linear_momentum_drift, (b.linear - b0.linear).norm() / Ls);
  if (Js > 0)
    sum.angular_momentum_drift = std::max(sum.angular_momentum_drift, (b.angular - b0.angular).norm() / Js);
}

std::string failure_message(int step, double t, double h, const time::ReducedStep& r) {
  std::ostringstream out;
  out << "step " << step + 1 << " (t = " << t << " → " << t + h << ") did not converge: " << r.failure
      << "; residual history: " << solve::format_history(r.residuals)
      << ". Hint: reduce time.step, or check the material and initial velocities.";
  return out.str();
}

/// Most halvings of a step whose Newton solve fails (time/step_reduction.hpp): substeps down to h/16.
constexpr int max_step_halvings = 4;

/// The linear solver named by solver.linear (validated by the scene: auto, direct, iterative,
/// petsc_gamg); auto picks petsc_gamg from model::SolverSpec::auto_iterative_elements elements on,
/// where it overtakes the LU (docs/measurements.md, "Linear solvers"), direct below.
solve::LinearMethod linear_method(const Model& m) {
  if (m.solver.linear == "iterative") return solve::LinearMethod::iterative;
  if (m.solver.linear == "petsc_gamg") return solve::LinearMethod::petsc_gamg;
  if (m.solver.linear == "auto" && m.mesh.element_count() >= model::SolverSpec::auto_iterative_elements)
    return solve::LinearMethod::petsc_gamg;
  return solve::LinearMethod::direct;
}

/// The log line naming the linear solver of the run (and why, for auto).
std::string linear_solver_line(const Model& m) {
  const solve::LinearMethod method = linear_method(m);
  const std::string name = method == solve::LinearMethod::petsc_gamg ? "petsc_gamg (PETSc GMRES + GAMG, rigid-body modes)"
                           : method == solve::LinearMethod::iterative ? "iterative (BiCGSTAB, Jacobi preconditioner)"
                                                                       : "direct (UMFPACK LU)";
  if (m.solver.linear != "auto") return "linear solver: " + name;
  return "linear solver: auto → " + name + ": " + std::to_string(m.mesh.element_count()) + " elements, petsc_gamg from " +
         std::to_string(model::SolverSpec::auto_iterative_elements);
}

/// The log's line on the Krylov solves of a run (none with the direct solver).
std::string krylov_line(const solve::LinearSolver& linear) {
  char line[200];
  std::snprintf(line, sizeof line,
                "linear solver: %ld Krylov solves, %.1f iterations per solve, at most %d, %ld fell back to LU",
                linear.krylov_solves(), double(linear.krylov_iterations()) / double(linear.krylov_solves()),
                linear.krylov_max_iterations(), linear.krylov_fallbacks());
  return line;
}

/// Newton from the scene's solver settings. Factorisations are kept while they contract the residual
/// by 5 per iteration with Broyden's update (and reach the tolerance within the budget): on the contact
/// scenes a refactorisation costs as much as ~20 reused solves (bench/contact_ball.cpp); NewtonOptions
/// holds the reuse rule (docs/measurements.md, "Newton on hard impacts").
solve::NewtonOptions newton_options(const Model& m) {
  solve::NewtonOptions o;
  o.linear = linear_method(m);
  // A GAMG setup is cheap next to an LU but each GMRES solve costs 13–24 multigrid cycles: a fresh
  // Jacobian per iteration halved Newton's iterations (4 instead of 8.5 per step) and the wall time
  // (21.8 s instead of 45.6 s, 2 steps of the 27,648-hex8 tumbling sphere). The AMG solver itself keeps
  // its setup for the new matrix while GMRES converges about as fast (petsc_amg_solver.cpp).
  if (o.linear == solve::LinearMethod::petsc_gamg) o.reuse_factorization = false;
  o.tolerance = m.solver.tolerance;
  o.max_iterations = m.solver.max_iterations;
  const bool penalty = std::any_of(m.contact.begin(), m.contact.end(), [](const model::ContactPair& c) {
    return c.enforcement == model::Enforcement::penalty;
  });
  if (penalty) o.max_residual_growth = 1;  // line search: penalty and the return map are non-smooth (§5.2)
  return o;
}

/// Positions, velocities and, with contact, the nodal contact pressure (lagrange_term.hpp).
model::Frame frame_of(const time::State& s, const Problem& p) {
  model::Frame f{s.t, s.x, s.v, {}};
  if (p.contact.empty()) return f;
  f.contact_pressure = Eigen::VectorXd::Zero(s.x.size() / 3);
  for (const auto& term : p.contact) term->contact_pressure(f.contact_pressure);
  return f;
}

/// What a run reports, remembered for its checkpoints: series rows and frames go to the observer and, when
/// the run keeps checkpoints, into the checkpoint (rows) and its directory (frames).
class Recorder {
 public:
  Recorder(model::Observer& observer, output::CheckpointStore* store) : observer_(observer), store_(store) {}
  void step(const model::StepRow& row) {
    observer_.step(row);
    if (store_) rows_.push_back(row);
  }
  void frame(int step, const model::Frame& frame) {
    observer_.frame(frame);
    if (!store_) return;
    store_->write_frame(static_cast<int>(frame_steps_.size()), frame);
    frame_steps_.push_back(step);
  }
  /// Gives the observer the rows and frames up to the checkpoint again, in the order the run gave them.
  void replay(const output::Checkpoint& c) {
    size_t k = 0;
    for (const model::StepRow& row : c.rows) {
      observer_.step(row);
      for (; k < c.frame_steps.size() && c.frame_steps[k] == row.step; ++k)
        observer_.frame(store_->read_frame(static_cast<int>(k)));
    }
    rows_ = c.rows;
    frame_steps_ = c.frame_steps;
  }
  const std::vector<model::StepRow>& rows() const { return rows_; }
  const std::vector<int>& frame_steps() const { return frame_steps_; }

 private:
  model::Observer& observer_;
  output::CheckpointStore* store_;
  std::vector<model::StepRow> rows_;
  std::vector<int> frame_steps_;
};

/// When a run writes a checkpoint: after every checkpoint_every-th step, or once checkpoint_seconds of wall
/// time passed since the last; never after the last step (the result has it all). A checkpoint makes the
/// next step refactorise, so where checkpoints may land must not depend on wall time, or a run would
/// compute other round-off when slower (beside another job): by wall time they land only on every
/// wall_time_stride-th step, and the run refactorises after each of those whether one is written or not.
class CheckpointSchedule {
 public:
  static constexpr int wall_time_stride = 10;
  explicit CheckpointSchedule(const model::OutputSpec& output) : output_(output), last_(Clock::now()) {}
  /// Whether a checkpoint may follow `step`: the run refactorises after it (step-driven, never wall time).
  bool may_land(int step, int steps) const {
    if (step >= steps) return false;
    return step % (output_.checkpoint_every > 0 ? output_.checkpoint_every : wall_time_stride) == 0;
  }
  bool due(int step, int steps) const {
    if (!may_land(step, steps)) return false;
    return output_.checkpoint_every > 0 || seconds_since(last_) >= output_.checkpoint_seconds;
  }
  void written() { last_ = Clock::now(); }

 private:
  model::OutputSpec output_;
  Clock::time_point last_;
};

/// The checkpoint to resume from, checked against the run: the same scene, step size and terms.
output::Checkpoint load_checkpoint(const output::CheckpointStore& store, const Model& m,
                                   const std::vector<time::Term*>& terms) {
  output::Checkpoint c;
  try {
    c = store.read();
  } catch (const std::exception& e) {
    throw CheckpointError("cannot resume from " + store.state_file().string() + ": " + e.what());
  }
  const auto refuse = [&](const std::string& why) {
    throw CheckpointError("cannot resume from " + store.state_file().string() + ": " + why);
  };
  if (c.scene != m.scene.dump()) refuse("it was written for another scene");
  if (c.step_size != m.time.step) refuse("it was written with another time.step");
  if (c.terms.size() != terms.size()) refuse("it holds " + std::to_string(c.terms.size()) + " terms, the run has " +
                                             std::to_string(terms.size()));
  for (size_t k = 0; k < terms.size(); ++k)
    if (c.terms[k].first != terms[k]->name()) refuse("term " + std::to_string(k) + " is " + c.terms[k].first);
  if (c.state.x.size() != m.dof_count() || c.state.v.size() != m.dof_count() || c.state.a.size() != m.dof_count())
    refuse("its state does not have " + std::to_string(m.dof_count()) + " dofs");
  if (c.rows.empty() || c.rows.back().step != c.state.step) refuse("its series does not end at its step");
  for (size_t k = 0; k < c.frame_steps.size(); ++k)
    if (!store.has_frame(static_cast<int>(k))) refuse("frame " + std::to_string(k) + " is missing");
  return c;
}

/// The checkpoint of the run at the end of step s.step.
output::Checkpoint checkpoint_of(const Model& m, const time::State& s, const std::vector<time::Term*>& terms,
                                 const model::Summary& sum, const Recorder& recorder) {
  output::Checkpoint c;
  c.scene = m.scene.dump();
  c.state = s;
  c.step_size = m.time.step;
  for (const time::Term* t : terms) c.terms.emplace_back(t->name(), t->save_state());
  c.summary = sum;
  c.rows = recorder.rows();
  c.frame_steps = recorder.frame_steps();
  return c;
}

}  // namespace

model::Summary simulate(const Model& m, model::Observer& observer, const CancelFlag* cancel,
                        const Checkpoints& checkpoints) {
  const auto wall0 = Clock::now();
  Problem p = build_problem(m);
  std::vector<time::Term*> terms{p.elasticity.get()};
  if (p.gravity) terms.push_back(p.gravity.get());
  const size_t first_contact = terms.size();
  for (const auto& c : p.contact) terms.push_back(c.get());
  time::Integrator integrator(p.mass, terms, p.fixed, time::make_scheme(m.time),
                              newton_options(m), p.length_scale, p.total_mass);
  time::State s;
  s.x = m.mesh.reference_positions();
  s.v = initial_velocity(m, p, s.x);
  s.a = Eigen::VectorXd::Zero(s.x.size());
  integrator.initialize(s);

  std::optional<output::CheckpointStore> store;
  if (!checkpoints.directory.empty()) store.emplace(checkpoints.directory);
  std::optional<output::Checkpoint> resumed;
  if (store && checkpoints.resume && store->exists()) resumed = load_checkpoint(*store, m, terms);

  const model::SeriesLayout layout = series_layout(m);
  const int steps = m.time.steps();
  double output_seconds = 0;  // series rows, frames and the observer's calls
  auto t_out = Clock::now();
  Recorder recorder(observer, store ? &*store : nullptr);
  observer.begin(m, layout);
  if (m.solver.linear != "direct") observer.log(linear_solver_line(m));
  const Balance b0 = balance(p, s);  // the initial state, also when resuming: the drifts are against it
  model::Summary sum;
  if (resumed) {
    recorder.replay(*resumed);
    s = resumed->state;
    for (size_t k = 0; k < terms.size(); ++k) terms[k]->restore_state(resumed->terms[k].second, s.x, s.v);
    sum = resumed->summary;
    sum.resumed_from_step = s.step;
    observer.resumed(s.step);
    observer.log("resumed from step " + std::to_string(s.step) + " (t = " + std::to_string(s.t) +
                 ") of the checkpoint " + store->state_file().string() + ": computing steps " +
                 std::to_string(s.step + 1) + " to " + std::to_string(steps));
  } else {
    recorder.step(step_row(s, b0, contact_row(p, nullptr), layout, nullptr, 0.0));
    recorder.frame(0, frame_of(s, p));
  }
  output_seconds += seconds_since(t_out);

  sum.initial_energy = b0.total();
  auto finish = [&](bool completed) {
    sum.completed = completed;
    sum.steps = s.step;
    sum.end_time = s.t;
    sum.newton_iterations_per_step = s.step > 0 ? double(sum.newton_iterations) / s.step : 0.0;
    sum.wall_seconds = seconds_since(wall0);
    sum.linear_factorization_seconds = integrator.linear_factorization_seconds();
    sum.linear_solve_seconds = integrator.linear_solve_seconds();
    sum.linear_solver_seconds = sum.linear_factorization_seconds + sum.linear_solve_seconds;
    // Terms in the order given to the integrator: elasticity, gravity if any, then the contact pairs.
    sum.assembly_seconds = p.setup_seconds + integrator.inertia_seconds();
    sum.contact_seconds = p.setup_contact_seconds;
    for (size_t k = 0; k < terms.size(); ++k)
      (k < first_contact ? sum.assembly_seconds : sum.contact_seconds) += integrator.term_seconds(k);
    sum.output_seconds = output_seconds;
    sum.peak_memory_bytes = peak_resident_bytes();
    const solve::LinearSolver& linear = integrator.linear_solver();
    if (linear.krylov_solves() > 0)
      sum.krylov_iterations_per_solve = double(linear.krylov_iterations()) / double(linear.krylov_solves());
    sum.krylov_fallbacks = int(linear.krylov_fallbacks());
    if (linear.krylov_solves() > 0) observer.log(krylov_line(linear));
    if (!linear.preconditioner_description().empty())
      observer.log("linear solver: " + linear.preconditioner_description());
    observer.end(sum);
    return sum;
  };
  const auto log = [&](const std::string& line) { observer.log(line); };
  CheckpointSchedule schedule(m.output);
  for (int n = s.step + 1; n <= steps; ++n) {
    if (cancel && cancel->load()) return finish(false);
    const double h = std::min(m.time.step, m.time.end - s.t);
    const auto t0 = Clock::now();
    const int step0 = s.step;
    const double time0 = s.t;
    ContactRow c;
    const time::ReducedStep r = time::step_with_reduction(integrator, s, h, max_step_halvings, log,
                                                          [&] { add_substep(c, contact_row(p, &integrator)); });
    if (!r.converged) {
      const std::string message = failure_message(step0, time0, h, r);
      observer.log(message);
      finish(false);
      throw SolverError(message);
    }
    sum.newton_iterations += r.iterations;
    t_out = Clock::now();
    const Balance b = balance(p, s);
    update_drifts(sum, b0, b);
    sum.max_penetration = std::max(sum.max_penetration, c.max_penetration);
    sum.max_own_face_penetration = std::max(sum.max_own_face_penetration, c.own_face_penetration);
    sum.max_faceted_penetration = std::max(sum.max_faceted_penetration, c.faceted_penetration);
    recorder.step(step_row(s, b, c, layout, &r, seconds_since(t0)));
    if (m.output.frame_due(n, steps)) recorder.frame(n, frame_of(s, p));
    if (store && schedule.may_land(n, steps)) {
      if (schedule.due(n, steps)) {
        store->write(checkpoint_of(m, s, terms, sum, recorder));
        schedule.written();
      }
      integrator.forget_factorization();  // the next step as a run resumed from here computes it
    }
    output_seconds += seconds_since(t_out);
  }
  return finish(true);
}

}  // namespace stoss
