#include "core/time/generalized_alpha.hpp"

namespace stoss::time {

GeneralizedAlpha::GeneralizedAlpha(double alpha_m, double alpha_f, double beta, double gamma)
    : alpha_m_(alpha_m), alpha_f_(alpha_f), beta_(beta), gamma_(gamma) {}

GeneralizedAlpha GeneralizedAlpha::hht(double alpha) {
  return {0, -alpha, (1 - alpha) * (1 - alpha) / 4, 0.5 - alpha};  // (2.11)
}

GeneralizedAlpha GeneralizedAlpha::chung_hulbert(double rho_infinity) {
  const double alpha_m = (2 * rho_infinity - 1) / (rho_infinity + 1);  // (2.13)
  const double alpha_f = rho_infinity / (rho_infinity + 1);
  const double gamma = 0.5 - alpha_m + alpha_f;
  return {alpha_m, alpha_f, 0.25 * (1 - alpha_m + alpha_f) * (1 - alpha_m + alpha_f), gamma};
}

Eigen::VectorXd GeneralizedAlpha::acceleration(const State& s, double h, const Eigen::VectorXd& x_1) const {
  return (x_1 - s.x - h * s.v) / (beta_ * h * h) - (1 / (2 * beta_) - 1) * s.a;  // (2.10)
}

void GeneralizedAlpha::add_inertia(const State& s, double h, const solve::SparseMatrix& M,
                                   const Eigen::VectorXd& x_1, Eigen::VectorXd& R) const {
  const Eigen::VectorXd a_1 = acceleration(s, h, x_1);
  if (alpha_m_ == 0) {
    R.head(x_1.size()) += h * (M * a_1);  // h × (2.11)
    return;
  }
  R.head(x_1.size()) += h * (M * ((1 - alpha_m_) * a_1 + alpha_m_ * s.a));  // h × (2.12)
}

void GeneralizedAlpha::advance(State& s, double h, const Eigen::VectorXd& x_1) const {
  const Eigen::VectorXd a_1 = acceleration(s, h, x_1);
  s.v += h * ((1 - gamma_) * s.a + gamma_ * a_1);  // (2.10)
  s.a = a_1;
  s.x = x_1;
}

}  // namespace stoss::time
