#include "core/contact/lagrange/elements/mixed_element.hpp"

namespace stoss::contact {
namespace {
// Σ_j λ_j ∂∇̄g_j/∂π_b = ∂μ/∂π_b (17×17).
Matrix17 multiplier_derivative(const DiscreteGradient& dg, const Vector6& lambda) {
  Matrix17 dmu = Matrix17::Zero();
  for (int j = 0; j < 6; ++j) dmu += lambda[j] * dg.derivative[j];
  return dmu;
}
}  // namespace

MixedResult mixed_element(const Vector20& q_n, const Vector20& q_1, const Vector6& lambda, double f3,
                          double h) {
  const Vector20 q_m = 0.5 * (q_n + q_1);
  const Vector17 pi_a = invariants(q_n, f3), pi_b = invariants(q_1, f3);
  const Matrix17x20 B = invariant_jacobian(q_m);       // B_s = Dπ(q_m)
  const Matrix17x20 B_plus = invariant_jacobian(q_1);  // B⁺_s = Dπ(q_{n+1})
  const DiscreteGradient dg = discrete_gradient(pi_a, pi_b);
  const Vector17 mu = dg.value.transpose() * lambda;  // μ_s = ∇̄gᵀλ
  MixedResult out;
  out.Rq = h * B.transpose() * mu;  // (4.9)
  out.Rl = constraints(pi_b);       // (4.9) at t_{n+1}
  out.Kqq = h * (0.5 * invariant_hessian_contraction(mu) +
                 B.transpose() * multiplier_derivative(dg, lambda) * B_plus);  // (4.10)
  out.Kql = h * B.transpose() * dg.value.transpose();                          // (4.10)
  out.Klq = constraint_gradient(pi_b) * B_plus;                                // (4.10)
  out.g_n = constraints(pi_a);                                                 // (4.11)
  return out;
}

}  // namespace stoss::contact
