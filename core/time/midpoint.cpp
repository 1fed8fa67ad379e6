#include "core/time/midpoint.hpp"

namespace stoss::time {

void MidpointKinematics::add_inertia(const State& s, double h, const solve::SparseMatrix& M,
                                     const Eigen::VectorXd& x_1, Eigen::VectorXd& R) const {
  R.head(x_1.size()) += M * ((2.0 / h) * (x_1 - s.x) - 2.0 * s.v);  // (2.3)
}

Eigen::VectorXd MidpointKinematics::predict(const State& s, double h) const {
  if (s.a.size() != s.x.size()) return s.x + h * s.v;
  return s.x + h * (s.v - s.a);  // x_n + (h/2)(v_n + v_{n−1}), whatever the last step's size
}

void MidpointKinematics::advance(State& s, double h, const Eigen::VectorXd& x_1) const {
  const Eigen::VectorXd v_1 = (2.0 / h) * (x_1 - s.x) - s.v;  // (2.1)
  s.a = 0.5 * (v_1 - s.v);
  s.v = v_1;
  s.x = x_1;
}

}  // namespace stoss::time
