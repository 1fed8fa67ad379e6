#include "core/loads/surface_load.hpp"

#include "core/loads/face_quadrature.hpp"

namespace stoss::loads {
namespace {

std::vector<int> face_dofs(const mesh::Quad& face) {
  std::vector<int> dofs(12);
  for (int I = 0; I < 4; ++I)
    for (int k = 0; k < 3; ++k) dofs[3 * I + k] = 3 * face[I] + k;
  return dofs;
}

}  // namespace

SurfaceLoad::SurfaceLoad(std::vector<mesh::Quad> faces, Amplitude amplitude, double start_time)
    : faces_(std::move(faces)), amplitude_(std::move(amplitude)), t_(start_time) {}

void SurfaceLoad::register_blocks(solve::BlockPattern& pattern) {
  block_.clear();
  if (!follows_deformation()) return;
  for (const mesh::Quad& face : faces_) block_.push_back(pattern.add_block(face_dofs(face)));
}

SurfaceLoad::Evaluation SurfaceLoad::evaluation(const time::StepContext& step) const {
  const time::ForceRule& rule = step.rule;
  // The discrete-gradient rule has no configuration of its own: a load is taken at the midpoint (5b.4).
  const bool midpoint = rule.kind == time::ForceRule::Kind::discrete_gradient;
  const double theta = midpoint ? 0.5 : rule.theta;
  const double weight = midpoint ? 1 : rule.weight, previous_weight = midpoint ? 0 : rule.previous_weight;
  return {theta, weight, previous_weight, amplitude_(t_ + theta * step.h)};
}

void SurfaceLoad::begin_step(const time::StepContext& step, Eigen::VectorXd&) {
  // a(t_n) f(x_n): for the rules that weigh it, and for static steps' trapezoid work (5b.7b)
  if (evaluation(step).previous_weight == 0 && step.inertia) return;
  force_n_.resize(faces_.size());
  const double factor_n = amplitude_(t_);
  for (size_t k = 0; k < faces_.size(); ++k) {
    face_force(k, face_positions(faces_[k], step.x_n), force_n_[k], nullptr);
    force_n_[k] *= factor_n;
  }
}

void SurfaceLoad::face_step(const time::StepContext& step, const Evaluation& e, size_t k,
                            const Eigen::VectorXd& x_1, FaceVector& f, FaceMatrix* K) const {
  const FacePositions x_n = face_positions(faces_[k], step.x_n);
  const FacePositions x_theta = (1 - e.theta) * x_n + e.theta * face_positions(faces_[k], x_1);
  face_force(k, x_theta, f, K);
  f *= e.weight * e.factor;  // f_alg = w a(t_θ) f(x_θ) + w_n a(t_n) f(x_n) (5b.4)
  if (e.previous_weight != 0) f += e.previous_weight * force_n_[k];
  if (K) *K *= e.weight * e.theta * e.factor;
}

void SurfaceLoad::add(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                      solve::BlockPattern* K) const {
  const Evaluation e = evaluation(step);
  const bool tangent = K && follows_deformation();
  FaceVector f;
  FaceMatrix Kf;
  for (size_t k = 0; k < faces_.size(); ++k) {
    face_step(step, e, k, z, f, tangent ? &Kf : nullptr);
    for (int I = 0; I < 4; ++I) R.segment<3>(3 * faces_[k][I]) -= step.force_factor * f.segment<3>(3 * I);
    if (tangent) K->scatter(block_[k], -step.force_factor * Kf);
  }
}

Eigen::VectorXd SurfaceLoad::step_force(const time::StepContext& step, const Eigen::VectorXd& x_1) const {
  const Evaluation e = evaluation(step);
  Eigen::VectorXd out = Eigen::VectorXd::Zero(step.x_n.size());
  FaceVector f;
  for (size_t k = 0; k < faces_.size(); ++k) {
    face_step(step, e, k, x_1, f, nullptr);
    for (int I = 0; I < 4; ++I) out.segment<3>(3 * faces_[k][I]) += f.segment<3>(3 * I);
  }
  return out;
}

void SurfaceLoad::end_step(const time::StepContext& step, const Eigen::VectorXd& z) {
  const Eigen::Index n = step.x_n.size();
  const Eigen::VectorXd f = step_force(step, z.head(n));
  const Eigen::VectorXd dx = z.head(n) - step.x_n;
  double work = f.dot(dx);  // W_step = f_alg·Δx (5b.5)
  if (!step.inertia) {      // between two equilibria, the trapezoid rule (5b.7b)
    double start = 0;
    for (size_t k = 0; k < faces_.size(); ++k)
      start += force_n_[k].dot(face_positions(faces_[k], dx).reshaped());
    work = 0.5 * (start + work);
  }
  work_ += work;
  impulse_ += step.force_factor * f.reshaped(3, n / 3).rowwise().sum();
  t_ += step.h;
}

time::TermState SurfaceLoad::save_state() const {
  time::TermState state;
  state.reals["time"] = {t_};
  state.reals["work"] = {work_};
  state.reals["impulse"] = {impulse_[0], impulse_[1], impulse_[2]};
  return state;
}

void SurfaceLoad::restore_state(const time::TermState& state, const Eigen::VectorXd&,
                                const Eigen::VectorXd&) {
  t_ = state.real("time", 1)[0];
  work_ = state.real("work", 1)[0];
  const std::vector<double>& impulse = state.real("impulse", 3);
  impulse_ = Eigen::Vector3d(impulse[0], impulse[1], impulse[2]);
}

}  // namespace stoss::loads
