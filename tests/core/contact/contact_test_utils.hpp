#pragma once
/// @file Seeded random states and central finite differences for the contact kernel tests.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <random>

#include "core/contact/geometry/projection.hpp"
#include "core/contact/lagrange/invariants.hpp"
#include "core/contact/types.hpp"

namespace stoss::contact::test {

/// ‖a − b‖ / ‖b‖ (Frobenius).
template <class A, class B>
double relative_error(const A& a, const B& b) {
  return (a - b).norm() / std::max(b.norm(), 1e-300);
}

template <int n>
Eigen::Matrix<double, n, 1> random_vector(std::mt19937& rng, double scale = 1) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Matrix<double, n, 1> v;
  for (int i = 0; i < n; ++i) v[i] = scale * normal(rng);
  return v;
}

/// A random proper rotation (QR of a Gaussian matrix, det = +1).
inline Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  Eigen::Matrix3d M;
  M << random_vector<3>(rng), random_vector<3>(rng), random_vector<3>(rng);
  Eigen::Matrix3d R = Eigen::HouseholderQR<Eigen::Matrix3d>(M).householderQ();
  if (R.determinant() < 0) R.col(0) *= -1;
  return R;
}

/// A warped, distorted unit-size segment with a slave node above it (gap ≈ 0.2–0.3), rotated and
/// translated at random — the state of check_fd.py.
struct NtsState {
  Eigen::Vector3d slave;
  SegmentNodes nodes;
  Vector15 x() const { return element_vector(slave, nodes); }
};

inline NtsState random_nts_state(unsigned seed) {
  std::mt19937 rng(seed);
  SegmentNodes Y;
  Y << 0, 0, 0, 1, 0, 0.1, 1.1, 1, -0.05, 0, 0.9, 0.2;
  for (int K = 0; K < 4; ++K) Y.row(K) += random_vector<3>(rng, 0.02).transpose();
  const Eigen::Matrix3d R = random_rotation(rng);
  const Eigen::Vector3d t = random_vector<3>(rng);
  NtsState s;
  s.slave = R * Eigen::Vector3d(0.6, 0.4, 0.3) + t;
  for (int K = 0; K < 4; ++K) s.nodes.row(K) = (R * Y.row(K).transpose() + t).transpose();
  return s;
}

/// A mixed element state (q_n, q_{n+1}, λ) as in check_fd.py: d near n, ξ off the CPP, q_{n+1} a
/// random perturbation of q_n, λ random.
struct MixedState {
  Vector20 q_n, q_1;
  Vector6 lambda;
  double f3 = 0, h = 0.01;
};

inline MixedState random_mixed_state(unsigned seed, double step = 0.05) {
  const NtsState s = random_nts_state(seed);
  const Projection p = closest_point_projection(s.slave, s.nodes);
  std::mt19937 rng(seed + 1000);
  MixedState m;
  const Eigen::Vector3d d = p.frame.normal + random_vector<3>(rng, 0.01);
  m.q_n = mixed_coordinates(s.slave, s.nodes, d, p.xi + Eigen::Vector2d::Constant(0.05));
  m.q_1 = m.q_n + random_vector<20>(rng, step);
  m.lambda = random_vector<6>(rng);
  m.f3 = 0.01 * random_vector<1>(rng)[0];
  return m;
}

/// Central differences (f(z + εe_j) − f(z − εe_j)) / 2ε of a vector-valued f.
template <int n, class F>
auto fd_jacobian(F&& f, const Eigen::Matrix<double, n, 1>& z, double eps) {
  using Value = decltype(f(z));
  constexpr int m = Value::RowsAtCompileTime;
  Eigen::Matrix<double, m, n> J;
  for (int j = 0; j < n; ++j) {
    Eigen::Matrix<double, n, 1> zp = z, zm = z;
    zp[j] += eps;
    zm[j] -= eps;
    J.col(j) = (f(zp) - f(zm)) / (2 * eps);
  }
  return J;
}

/// FD step: 1e-6 × a length scale of the state (the segments here have unit size).
inline constexpr double fd_step = 1e-6;

}  // namespace stoss::contact::test
