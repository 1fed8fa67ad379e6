#include "core/time/static_scheme.hpp"

namespace stoss::time {

void Static::advance(State& s, double, const Eigen::VectorXd& x_1) const {
  s.x = x_1;
  s.v.setZero(x_1.size());
  s.a.setZero(x_1.size());
}

}  // namespace stoss::time
