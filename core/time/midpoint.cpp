#include "core/time/midpoint.hpp"

#include <cmath>

namespace stoss::time {

void MidpointKinematics::add_inertia(const State& s, double h, const solve::SparseMatrix& M,
                                     const Eigen::VectorXd& x_1, Eigen::VectorXd& R) const {
  R.head(x_1.size()) += M * ((2.0 / h) * (x_1 - s.x) - 2.0 * s.v);  // (2.3)
}

Eigen::VectorXd MidpointKinematics::predict(const State& s, double h) const {
  if (s.a.size() != s.x.size()) return s.x + h * s.v;
  // h_last = h for a last step shortened by the round-off of t (fixed steps keep their former digits)
  const double h_last = s.last_step > 0 && std::abs(s.last_step - h) > 1e-9 * h ? s.last_step : h;
  return s.x + h * s.v -
         (0.5 * h * h_last) * s.a;  // x_n + (h/2)(v_n + v_{n−1}), a_n = (v_n − v_{n−1})/h_last
}

void MidpointKinematics::advance(State& s, double h, const Eigen::VectorXd& x_1) const {
  const Eigen::VectorXd v_1 = (2.0 / h) * (x_1 - s.x) - s.v;  // (2.1)
  s.a = (v_1 - s.v) / h;
  s.last_step = h;
  s.v = v_1;
  s.x = x_1;
}

}  // namespace stoss::time
