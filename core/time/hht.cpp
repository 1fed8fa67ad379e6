#include "core/time/hht.hpp"

namespace stoss::time {

Hht::Hht(double alpha) : alpha_(alpha), beta_((1 - alpha) * (1 - alpha) / 4), gamma_(0.5 - alpha) {}

Eigen::VectorXd Hht::acceleration(const State& s, double h, const Eigen::VectorXd& x_1) const {
  return (x_1 - s.x - h * s.v) / (beta_ * h * h) - (1 / (2 * beta_) - 1) * s.a;  // (2.10)
}

void Hht::add_inertia(const State& s, double h, const solve::SparseMatrix& M, const Eigen::VectorXd& x_1,
                      Eigen::VectorXd& R) const {
  R.head(x_1.size()) += h * (M * acceleration(s, h, x_1));  // h × (2.11)
}

void Hht::advance(State& s, double h, const Eigen::VectorXd& x_1) const {
  const Eigen::VectorXd a_1 = acceleration(s, h, x_1);
  s.v += h * ((1 - gamma_) * s.a + gamma_ * a_1);  // (2.10)
  s.a = a_1;
  s.x = x_1;
}

}  // namespace stoss::time
