#include "core/time/integrator.hpp"

#include <cmath>

namespace stoss::time {

Integrator::Integrator(const solve::SparseMatrix& mass, std::vector<Term*> terms, std::vector<char> fixed,
                       std::unique_ptr<Scheme> scheme, solve::NewtonOptions options, double length_scale,
                       double total_mass)
    : mass_(mass),
      terms_(std::move(terms)),
      fixed_(std::move(fixed)),
      scheme_(std::move(scheme)),
      options_(options),
      length_scale_(length_scale),
      total_mass_(total_mass) {}

double Integrator::potential_energy(const Eigen::VectorXd& x) const {
  double V = 0;
  for (const Term* t : terms_) V += t->energy(x);
  return V;
}

int Integrator::prepare_unknowns() {
  int offset = static_cast<int>(mass_.rows());
  for (Term* t : terms_) {
    t->set_auxiliary_offset(offset);
    offset += t->auxiliary_count();
  }
  if (offset != auxiliary_layout_ || !pattern_.built()) rebuild_pattern(offset);
  return offset;
}

void Integrator::rebuild_pattern(int n) {
  pattern_.clear();
  mass_block_ = pattern_.add_sparse(mass_);
  for (Term* t : terms_) t->register_blocks(pattern_);
  pattern_.build(n);
  fixed_.resize(n, 0);
  auxiliary_layout_ = n;
}

void Integrator::initialize(State& s) {
  if (!scheme_->needs_initial_acceleration()) return;
  // M a_0 = f_ext − f_int(x_0): the terms' midpoint force at x_1 = x_n, divided by h = 1.
  const StepContext at_rest{s.x, s.v, 1.0, ForceRule::midpoint, 0.0};
  Eigen::VectorXd z = s.x;
  for (Term* t : terms_) t->begin_step(at_rest, z);
  Eigen::VectorXd R = Eigen::VectorXd::Zero(s.x.size());
  for (const Term* t : terms_) t->add(at_rest, s.x, R, nullptr);
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
}

solve::NewtonResult Integrator::step(State& s, double h, const std::function<void(const std::string&)>& log) {
  context_ = std::make_unique<StepContext>(StepContext{s.x, s.v, h, scheme_->force_rule(), scheme_->alpha()});
  state_ = &s;
  const int n = prepare_unknowns();
  Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
  z.head(s.x.size()) = s.x + h * s.v;  // predictor
  for (Eigen::Index i = 0; i < s.x.size(); ++i)
    if (fixed_[i]) z[i] = s.x[i];
  for (Term* t : terms_) t->begin_step(*context_, z);
  residual_scale_ = 2 * (mass_ * s.v).norm();
  scale_pending_ = true;
  solve::NewtonResult result = solve::newton_solve(*this, z, pattern_, solver_, options_, log);
  if (result.converged) {
    for (Term* t : terms_) t->end_step(*context_, z);
    scheme_->advance(s, h, z.head(s.x.size()));
    s.t += h;
    s.step += 1;
  }
  state_ = nullptr;
  return result;
}

void Integrator::evaluate(const Eigen::VectorXd& z, Eigen::VectorXd& R, solve::BlockPattern* A) {
  const double h = context_->h;
  R.setZero(z.size());
  scheme_->add_inertia(*state_, h, mass_, z.head(state_->x.size()), R);
  if (A) {
    A->zero();
    A->scatter_sparse(mass_block_, mass_, scheme_->inertia_jacobian_factor(h));
  }
  for (const Term* t : terms_) t->add(*context_, z, R, A);
  for (Eigen::Index i = 0; i < R.size(); ++i)
    if (fixed_[i]) R[i] = 0;
  if (A) A->eliminate(fixed_);
  if (scale_pending_) {
    // (2.3) has momentum units: scale by ‖2 M v_n‖, the predictor's force impulse, or a floor.
    const double floor = 1e-4 * total_mass_ * length_scale_ / h;
    residual_scale_ = std::max({residual_scale_, R.norm(), floor});
    scale_pending_ = false;
  }
}

double Integrator::residual_measure(const Eigen::VectorXd& R) const {
  const Eigen::Index nx = state_->x.size();
  const double position_rows = R.head(nx).norm() / residual_scale_;
  const double auxiliary_rows = R.size() > nx ? R.tail(R.size() - nx).norm() / length_scale_ : 0.0;
  return std::max(position_rows, auxiliary_rows);
}

double Integrator::increment_measure(const Eigen::VectorXd& dz) const {
  return dz.head(state_->x.size()).norm() / length_scale_;
}

}  // namespace stoss::time
