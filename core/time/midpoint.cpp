#include "core/time/midpoint.hpp"

namespace stoss::time {

void MidpointKinematics::add_inertia(const State& s, double h, const solve::SparseMatrix& M,
                                     const Eigen::VectorXd& x_1, Eigen::VectorXd& R) const {
  R.head(x_1.size()) += M * ((2.0 / h) * (x_1 - s.x) - 2.0 * s.v);  // (2.3)
}

void MidpointKinematics::advance(State& s, double h, const Eigen::VectorXd& x_1) const {
  s.v = (2.0 / h) * (x_1 - s.x) - s.v;  // (2.1)
  s.x = x_1;
}

}  // namespace stoss::time
