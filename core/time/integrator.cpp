#include "core/time/integrator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace stoss::time {
namespace {

/// Adds the wall time of its scope to `total` (the timing hooks of the run summary).
class Stopwatch {
 public:
  explicit Stopwatch(double& total) : total_(total), t0_(std::chrono::steady_clock::now()) {}
  ~Stopwatch() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count(); }
  Stopwatch(const Stopwatch&) = delete;
  Stopwatch& operator=(const Stopwatch&) = delete;

 private:
  double& total_;
  std::chrono::steady_clock::time_point t0_;
};

/// Appends a later Newton solve of the same step to the step's record.
void merge(solve::NewtonResult& total, const solve::NewtonResult& pass) {
  total.converged = pass.converged;
  total.iterations += pass.iterations;
  total.backtracks += pass.backtracks;
  total.residuals.insert(total.residuals.end(), pass.residuals.begin(), pass.residuals.end());
  total.failure = pass.failure;
}

/// M with the rows and columns of fixed dofs replaced by identity rows (SPD for a consistent mass).
solve::SparseMatrix free_mass(const solve::SparseMatrix& M, const std::vector<char>& fixed) {
  solve::SparseMatrix out = M;
  for (int c = 0; c < out.outerSize(); ++c)
    for (solve::SparseMatrix::InnerIterator it(out, c); it; ++it)
      if (fixed[c] || fixed[it.row()]) it.valueRef() = it.row() == c ? 1.0 : 0.0;
  return out;
}

}  // namespace

Integrator::Integrator(const solve::SparseMatrix& mass, std::vector<Term*> terms, std::vector<char> fixed,
                       std::unique_ptr<Scheme> scheme, solve::NewtonOptions options, double length_scale,
                       double total_mass)
    : mass_(mass),
      terms_(std::move(terms)),
      fixed_(std::move(fixed)),
      scheme_(std::move(scheme)),
      options_(options),
      length_scale_(length_scale),
      total_mass_(total_mass),
      term_seconds_(terms_.size(), 0.0) {
  any_fixed_ = std::find(fixed_.begin(), fixed_.end(), char(1)) != fixed_.end();
}

double Integrator::potential_energy(const Eigen::VectorXd& x) const {
  double V = 0;
  for (const Term* t : terms_) V += t->energy(x);
  return V;
}

int Integrator::lay_out_auxiliaries() {
  int offset = static_cast<int>(mass_.rows());
  for (Term* t : terms_) {
    t->set_auxiliary_offset(offset);
    offset += t->auxiliary_count();
  }
  return offset;
}

int Integrator::prepare_unknowns() {
  const int n = lay_out_auxiliaries();
  bool structure_changed = structure_generations_.size() != terms_.size();
  for (size_t k = 0; k < terms_.size() && !structure_changed; ++k)
    structure_changed = structure_generations_[k] != terms_[k]->structure_generation();
  if (n != auxiliary_layout_ || !pattern_.built() || structure_changed) rebuild_pattern(n);
  return n;
}

void Integrator::rebuild_pattern(int n) {
  {
    Stopwatch assembly(inertia_seconds_);
    pattern_.clear();
    mass_block_ = pattern_.add_sparse(mass_, inertia_rows_.empty() ? nullptr : &inertia_rows_);
  }
  for (size_t k = 0; k < terms_.size(); ++k) {
    Stopwatch term(term_seconds_[k]);
    terms_[k]->register_blocks(pattern_);
  }
  Stopwatch assembly(inertia_seconds_);  // the pattern's build: no term runs below
  pattern_.build(n);
  fixed_.resize(mass_.rows());
  fixed_.resize(n, 0);
  auxiliary_layout_ = n;
  structure_generations_.clear();
  for (const Term* t : terms_) structure_generations_.push_back(t->structure_generation());
}

void Integrator::map_velocity(State& s) const {
  if (velocity_map_.size() == 0) return;
  s.v = velocity_map_ * s.v;  // docs/theory.md §4.6.1
  if (s.a.size() == s.v.size()) s.a = velocity_map_ * s.a;
}

void Integrator::initialize(State& s) {
  map_velocity(s);
  if (!scheme_->needs_initial_acceleration()) return;
  // M a_0 = f_ext − f_int(x_0): the terms' midpoint force at x_1 = x_n, divided by h = 1.
  const StepContext at_rest{s.x, s.v, 1.0, ForceRule::midpoint()};
  // The terms' auxiliary unknowns (contact multipliers, 0: no contact force at rest) laid out after the
  // positions, so that no term adds the rows of its own on a position row.
  Eigen::VectorXd z = Eigen::VectorXd::Zero(lay_out_auxiliaries());
  z.head(s.x.size()) = s.x;
  for (size_t k = 0; k < terms_.size(); ++k) {
    Stopwatch term(term_seconds_[k]);
    terms_[k]->begin_step(at_rest, z);
  }
  Eigen::VectorXd R = Eigen::VectorXd::Zero(z.size());
  for (size_t k = 0; k < terms_.size(); ++k) {
    Stopwatch term(term_seconds_[k]);
    terms_[k]->add(at_rest, z, R, nullptr);
  }
  R.conservativeResize(s.x.size());
  solve::BlockPattern M;
  const int block = M.add_sparse(mass_);
  M.build(static_cast<int>(mass_.rows()));
  M.scatter_sparse(block, mass_, 1.0);
  M.eliminate(fixed_);
  for (Eigen::Index i = 0; i < R.size(); ++i)
    if (fixed_[i]) R[i] = 0;
  solve::LinearSolver lu;
  lu.factorize(M);
  s.a = -lu.solve(R);
  initial_factorization_seconds_ += lu.factorization_seconds();
  initial_solve_seconds_ += lu.solve_seconds();
}

/// (2.3) of the step t_n → t_n + h: the scheme's inertia plus every term's rows, measured in the scales of
/// §2.1. Made by Integrator::step for one step; h and the state are its own, never the integrator's.
class Integrator::StepEquations final : public solve::NonlinearSystem {
 public:
  StepEquations(Integrator& owner, const State& s, double h, const LogFunction* log, bool may_cut)
      : owner_(owner), state_(s), context_{s.x,     s.v,
                                           h,       owner.scheme_->force_rule(),
                                           log,     owner.scheme_->force_factor(h),
                                           may_cut, owner.scheme_->has_inertia()} {}
  const StepContext& context() const { return context_; }
  /// The residual scale starts at ‖2 M v_n‖; the first evaluation raises it to the predictor's residual.
  void reset_scale() {
    residual_scale_ = 2 * (owner_.mass_ * state_.v).norm();
    scale_pending_ = true;
  }

  void evaluate(const Eigen::VectorXd& z, Eigen::VectorXd& R, solve::BlockPattern* A) override {
    const double h = context_.h;
    {
      Stopwatch assembly(owner_.inertia_seconds_);
      R.setZero(z.size());
      owner_.scheme_->add_inertia(state_, h, owner_.mass_, z.head(state_.x.size()), R);
      if (A) {
        A->zero();
        A->scatter_sparse(owner_.mass_block_, owner_.mass_, owner_.scheme_->inertia_jacobian_factor(h));
      }
    }
    for (size_t k = 0; k < owner_.terms_.size(); ++k) {
      Stopwatch term(owner_.term_seconds_[k]);
      owner_.terms_[k]->add(context_, z, R, A);
    }
    Stopwatch assembly(owner_.inertia_seconds_);
    if (owner_.any_fixed_) {  // the held rows, before elimination: the reaction (Integrator::reaction)
      owner_.held_rows_ = R.head(state_.x.size());
      owner_.held_rows_at_ = z.head(state_.x.size());
    }
    for (Eigen::Index i = 0; i < R.size(); ++i)
      if (owner_.fixed_[i]) R[i] = 0;
    if (A) A->eliminate(owner_.fixed_);
    if (scale_pending_) {
      // (2.3) has momentum units: scale by ‖2 M v_n‖, the predictor's force impulse, or a floor.
      const double floor = 1e-4 * owner_.total_mass_ * owner_.length_scale_ / h;
      residual_scale_ = std::max({residual_scale_, R.head(state_.x.size()).norm(), floor});
      scale_pending_ = false;
    }
  }

  double residual_measure(const Eigen::VectorXd& R) const override {
    double measure = R.head(state_.x.size()).norm() / residual_scale_;
    for (const Term* t : owner_.terms_)
      measure = std::max(measure, t->auxiliary_residual_measure(R, scales()));
    return measure;
  }

  double increment_measure(const Eigen::VectorXd& dz) const override {
    double measure = dz.head(state_.x.size()).norm() / owner_.length_scale_;
    for (const Term* t : owner_.terms_)
      measure = std::max(measure, t->auxiliary_increment_measure(dz, scales()));
    return measure;
  }

 private:
  MeasureScales scales() const { return {residual_scale_, owner_.length_scale_}; }

  Integrator& owner_;
  const State& state_;
  const StepContext context_;
  double residual_scale_ = 0;
  bool scale_pending_ = false;
};

Eigen::VectorXd Integrator::relayout(const StepContext& step, const Eigen::VectorXd& positions) {
  Eigen::VectorXd z = Eigen::VectorXd::Zero(prepare_unknowns());
  z.head(positions.size()) = positions;
  for (size_t k = 0; k < terms_.size(); ++k) {
    Stopwatch term(term_seconds_[k]);
    terms_[k]->initialize_auxiliaries(step, z);
  }
  return z;
}

solve::NewtonResult Integrator::solve_with_active_set(StepEquations& equations, Eigen::VectorXd& z,
                                                      const LogFunction& log) {
  solve::NewtonResult total;
  const Eigen::Index nx = mass_.rows();
  for (passes_ = 1;; ++passes_) {
    merge(total, solve::newton_solve(equations, z, pattern_, solver_, options_, log));
    if (!total.converged) return total;
    bool changed = false;
    for (size_t k = 0; k < terms_.size(); ++k) {  // §3.5
      Stopwatch term(term_seconds_[k]);
      changed = terms_[k]->update_active_set(equations.context(), z) || changed;
    }
    if (!changed || requested_cut() < 1) return total;  // a cut: the step is solved again, shorter (§4.6.2)
    if (passes_ == max_active_set_passes) {
      total.converged = false;
      total.failure = "the contact active set did not settle in " + std::to_string(passes_) + " passes";
      return total;
    }
    z = relayout(equations.context(), z.head(nx));
  }
}

double Integrator::requested_cut() const {
  double cut = 1;
  for (const Term* t : terms_) cut = std::min(cut, t->requested_cut());
  return cut;
}

solve::NewtonResult Integrator::attempt(const State& s, StepEquations& equations, Eigen::VectorXd& z,
                                        const LogFunction& log) {
  const StepContext& step = equations.context();
  for (size_t k = 0; k < terms_.size(); ++k) {
    Stopwatch term(term_seconds_[k]);
    terms_[k]->prepare_step(step);
  }
  z = Eigen::VectorXd::Zero(prepare_unknowns());
  z.head(s.x.size()) = scheme_->predict(s, step.h);
  for (Eigen::Index i = 0; i < s.x.size(); ++i)
    if (fixed_[i]) z[i] = s.x[i];
  for (size_t k = 0; k < terms_.size(); ++k) {
    Stopwatch term(term_seconds_[k]);
    terms_[k]->begin_step(step, z);
  }
  equations.reset_scale();
  solver_.set_coordinates(s.x);  // rigid-body modes for an AMG linear solver
  return solve_with_active_set(equations, z, log);
}

solve::NewtonResult Integrator::step(State& s, double h, const LogFunction& log) {
  correction_energy_ = 0;
  solve::NewtonResult total;
  for (int cuts = 0;; ++cuts) {
    StepEquations equations(*this, s, h, log ? &log : nullptr, cuts < max_event_cuts);
    Eigen::VectorXd z;
    const solve::NewtonResult pass = attempt(s, equations, z, log);
    if (cuts == 0)
      total = pass;
    else
      merge(total, pass);
    if (!total.converged) return total;
    const double cut = requested_cut();
    if (cut < 1 && equations.context().may_cut) {  // §4.6.2: end the step at the located event
      h *= cut;
      continue;
    }
    finish(s, equations, z);
    advanced_ = h;
    return total;
  }
}

void Integrator::take_reaction(StepEquations& equations, const Eigen::VectorXd& z) {
  const Eigen::Index nx = mass_.rows();
  if (held_rows_at_.size() != nx || held_rows_at_ != z.head(nx)) {  // the last evaluation was elsewhere
    Eigen::VectorXd R;
    equations.evaluate(z, R, nullptr);
  }
  reaction_ = Eigen::VectorXd::Zero(nx);
  const double factor = equations.context().force_factor;
  for (Eigen::Index i = 0; i < nx; ++i)
    if (fixed_[i])
      reaction_[i] = held_rows_[i] / factor;  // R_i = h r_i at a held dof (docs/theory.md (5b.8))
}

void Integrator::finish(State& s, StepEquations& equations, const Eigen::VectorXd& z) {
  const StepContext& step = equations.context();
  const double h = step.h;
  if (any_fixed_) {
    take_reaction(equations, z);
    for (size_t k = 0; k < terms_.size(); ++k) terms_[k]->take_reaction(step, z, reaction_);
  }
  Eigen::VectorXd impulse = Eigen::VectorXd::Zero(s.x.size());
  double jump = 0;
  for (size_t k = 0; k < terms_.size(); ++k) {
    Stopwatch term(term_seconds_[k]);
    terms_[k]->add_impact_impulse(step, z, impulse, jump);
    terms_[k]->end_step(step, z);
  }
  // The step's context refers to s.x and s.v: nothing reads it once s advances.
  scheme_->advance(s, h, z.head(s.x.size()));
  if (impulse.squaredNorm() > 0) correct_velocity(s, std::move(impulse), jump);
  map_velocity(s);
  s.t += h;
  s.step += 1;
}

void Integrator::correct_velocity(State& s, Eigen::VectorXd b, double energy_jump) {
  if (!mass_solver_) {
    mass_solver_ = std::make_unique<Eigen::SimplicialLDLT<solve::SparseMatrix>>(free_mass(mass_, fixed_));
  }
  for (Eigen::Index i = 0; i < b.size(); ++i)
    if (fixed_[i]) b[i] = 0;
  const Eigen::VectorXd u = mass_solver_->solve(b);  // u = M⁻¹ b (4.12)
  const double a = b.dot(u), beta = b.dot(s.v);
  if (!(a > 0)) return;
  const double discriminant = std::max(beta * beta - 2 * a * energy_jump, 0.0);
  const double gamma = (-beta - std::sqrt(discriminant)) / a;  // the root with γ < 0 (4.12)
  s.v += gamma * u;
  correction_energy_ = gamma * beta + 0.5 * gamma * gamma * a;
}

}  // namespace stoss::time
