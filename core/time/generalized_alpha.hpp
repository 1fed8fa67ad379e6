#pragma once
/// @file The Newmark family with α-weighted balance: HHT-α (docs/theory.md §2.4) and generalized-α
/// (Chung & Hulbert 1993, §2.5). Dissipative engineering baselines: neither conserves energy nor angular
/// momentum in nonlinear problems.

#include "core/time/scheme.hpp"

namespace stoss::time {

/// M [(1−α_m) a_{n+1} + α_m a_n] + (1−α_f) f(x_{n+1}) + α_f f(x_n) = f_ext (2.12), Newmark updates (2.10).
class GeneralizedAlpha : public Scheme {
 public:
  /// HHT-α (2.11): α_m = 0, α_f = −α, β = (1 − α)²/4, γ = ½ − α.
  static GeneralizedAlpha hht(double alpha);
  /// Chung–Hulbert parameters from the spectral radius at infinite frequency ρ∞ ∈ [0, 1] (2.13).
  static GeneralizedAlpha chung_hulbert(double rho_infinity);

  ForceRule force_rule() const override { return ForceRule::end_point(1 - alpha_f_, alpha_f_); }
  void add_inertia(const State& s, double h, const solve::SparseMatrix& M, const Eigen::VectorXd& x_1,
                   Eigen::VectorXd& R) const override;
  double inertia_jacobian_factor(double h) const override { return (1 - alpha_m_) / (beta_ * h); }
  void advance(State& s, double h, const Eigen::VectorXd& x_1) const override;
  bool needs_initial_acceleration() const override { return true; }

  double alpha_m() const { return alpha_m_; }
  double alpha_f() const { return alpha_f_; }
  double beta() const { return beta_; }
  double gamma() const { return gamma_; }

 private:
  GeneralizedAlpha(double alpha_m, double alpha_f, double beta, double gamma);
  /// a_{n+1} from the Newmark update (2.10) solved for the acceleration.
  Eigen::VectorXd acceleration(const State& s, double h, const Eigen::VectorXd& x_1) const;
  double alpha_m_, alpha_f_, beta_, gamma_;
};

}  // namespace stoss::time
