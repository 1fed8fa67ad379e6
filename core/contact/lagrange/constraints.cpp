#include "core/contact/lagrange/constraints.hpp"

#include "core/contact/geometry/segment.hpp"

namespace stoss::contact {
namespace {
constexpr int pairs[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};

// Indices into π (0-based): π1 = 0, P = 1–3, ξ = 4–5, π7 = 6, π8 = 7, Q = 8–10, Π = 11–16.
constexpr int i_r = 0, i_P = 1, i_xi1 = 4, i_xi2 = 5, i_f3 = 6, i_dd = 7, i_Q = 8, i_Pi = 11;

// N̂ = (N_2, N_3, N_4) and its derivatives at ξ.
struct ReducedShape {
  Eigen::Vector3d N, N1, N2, N12;
};

ReducedShape reduced_shape(const Eigen::Vector2d& xi) {
  const BilinearShape s = bilinear_shape(xi);
  return {s.N.tail<3>(), s.dN.col(0).tail<3>(), s.dN.col(1).tail<3>(), s.d2N12.tail<3>()};
}

// Adds v at (i, j) and (j, i) (once if i = j).
void put_symmetric(Matrix17& H, int i, int j, double v) {
  H(i, j) += v;
  if (i != j) H(j, i) += v;
}

template <int n>
void put_symmetric(Matrix17& H, int i, int j0, const Eigen::Matrix<double, n, 1>& v) {
  for (int l = 0; l < n; ++l) put_symmetric(H, i, j0 + l, v[l]);
}
}  // namespace

InvariantParts split_invariants(const Vector17& pi) {
  InvariantParts p;
  p.P = pi.segment<3>(i_P);
  p.xi = pi.segment<2>(i_xi1);
  p.Q = pi.segment<3>(i_Q);
  for (int l = 0; l < 6; ++l) p.Pi(pairs[l][0], pairs[l][1]) = p.Pi(pairs[l][1], pairs[l][0]) = pi[i_Pi + l];
  return p;
}

Vector6 sym_pairs(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  Vector6 s;
  for (int l = 0; l < 6; ++l) {
    const int i = pairs[l][0], j = pairs[l][1];
    s[l] = i == j ? a[i] * b[i] : a[i] * b[j] + a[j] * b[i];  // §4.3.5
  }
  return s;
}

Vector6 constraints(const Vector17& pi) {
  const InvariantParts p = split_invariants(pi);
  const ReducedShape s = reduced_shape(p.xi);
  Vector6 g;
  g[0] = pi[i_r] - s.N.dot(p.P) - pi[i_f3];     // (4.3) gap
  g[1] = s.N1.dot(p.P);                         // (4.3) d ⊥ τ_1
  g[2] = s.N2.dot(p.P);                         // (4.3) d ⊥ τ_2
  g[3] = 0.5 * (pi[i_dd] - 1);                  // (4.3) |d| = 1
  g[4] = s.N1.dot(p.Q) - s.N1.dot(p.Pi * s.N);  // (4.3) CPP α = 1
  g[5] = s.N2.dot(p.Q) - s.N2.dot(p.Pi * s.N);  // (4.3) CPP α = 2
  return g;
}

Matrix6x17 constraint_gradient(const Vector17& pi) {
  const InvariantParts p = split_invariants(pi);
  const ReducedShape s = reduced_shape(p.xi);
  const double cross = s.N12.dot(p.Q) - s.N12.dot(p.Pi * s.N);
  Matrix6x17 G = Matrix6x17::Zero();
  G(0, i_r) = 1;  // (4.4) ∇g_1
  G.block<1, 3>(0, i_P) = -s.N.transpose();
  G(0, i_xi1) = -s.N1.dot(p.P);
  G(0, i_xi2) = -s.N2.dot(p.P);
  G(0, i_f3) = -1;
  G.block<1, 3>(1, i_P) = s.N1.transpose();  // (4.4) ∇g_2
  G(1, i_xi2) = s.N12.dot(p.P);
  G.block<1, 3>(2, i_P) = s.N2.transpose();  // (4.4) ∇g_3
  G(2, i_xi1) = s.N12.dot(p.P);
  G(3, i_dd) = 0.5;                          // (4.4) ∇g_4
  G.block<1, 3>(4, i_Q) = s.N1.transpose();  // (4.4) ∇g_5
  G.block<1, 6>(4, i_Pi) = -sym_pairs(s.N1, s.N).transpose();
  G(4, i_xi1) = -s.N1.dot(p.Pi * s.N1);
  G(4, i_xi2) = cross - s.N1.dot(p.Pi * s.N2);
  G.block<1, 3>(5, i_Q) = s.N2.transpose();  // (4.4) ∇g_6
  G.block<1, 6>(5, i_Pi) = -sym_pairs(s.N2, s.N).transpose();
  G(5, i_xi1) = cross - s.N2.dot(p.Pi * s.N1);
  G(5, i_xi2) = -s.N2.dot(p.Pi * s.N2);
  return G;
}

std::array<Matrix17, 6> constraint_hessians(const Vector17& pi) {
  const InvariantParts p = split_invariants(pi);
  const ReducedShape s = reduced_shape(p.xi);
  std::array<Matrix17, 6> H;
  for (Matrix17& Hk : H) Hk.setZero();
  put_symmetric(H[0], i_xi1, i_xi2, -s.N12.dot(p.P));  // (4.5) H_1
  put_symmetric<3>(H[0], i_xi1, i_P, -s.N1);
  put_symmetric<3>(H[0], i_xi2, i_P, -s.N2);
  put_symmetric<3>(H[1], i_xi2, i_P, s.N12);                       // (4.5) H_2
  put_symmetric<3>(H[2], i_xi1, i_P, s.N12);                       // (4.5) H_3
  put_symmetric(H[4], i_xi1, i_xi2, -2 * s.N12.dot(p.Pi * s.N1));  // (4.5) H_5
  put_symmetric(H[4], i_xi2, i_xi2, -2 * s.N12.dot(p.Pi * s.N2));
  put_symmetric<3>(H[4], i_xi2, i_Q, s.N12);
  put_symmetric<6>(H[4], i_xi1, i_Pi, -sym_pairs(s.N1, s.N1));
  put_symmetric<6>(H[4], i_xi2, i_Pi, -sym_pairs(s.N12, s.N) - sym_pairs(s.N1, s.N2));
  put_symmetric(H[5], i_xi1, i_xi1, -2 * s.N12.dot(p.Pi * s.N1));  // (4.5) H_6
  put_symmetric(H[5], i_xi1, i_xi2, -2 * s.N12.dot(p.Pi * s.N2));
  put_symmetric<3>(H[5], i_xi1, i_Q, s.N12);
  put_symmetric<6>(H[5], i_xi1, i_Pi, -sym_pairs(s.N12, s.N) - sym_pairs(s.N2, s.N1));
  put_symmetric<6>(H[5], i_xi2, i_Pi, -sym_pairs(s.N2, s.N2));
  return H;
}

}  // namespace stoss::contact
