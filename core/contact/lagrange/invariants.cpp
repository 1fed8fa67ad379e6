#include "core/contact/lagrange/invariants.hpp"

#include <array>

namespace stoss::contact {
namespace {
// A quadratic invariant is a·b with a = Σ_j a_j q_j, b = Σ_j b_j q_j over the 3-blocks
// j = x_s, y_1, y_2, y_3, y_4, d of q (§4.3.4: a = P_a q, b = P_b q).
using BlockCombination = std::array<double, 6>;
struct QuadraticInvariant {
  bool quadratic;
  BlockCombination a, b;
};

constexpr BlockCombination none{0, 0, 0, 0, 0, 0};
constexpr BlockCombination r{1, -1, 0, 0, 0, 0};
constexpr BlockCombination e2{0, -1, 1, 0, 0, 0};
constexpr BlockCombination e3{0, -1, 0, 1, 0, 0};
constexpr BlockCombination e4{0, -1, 0, 0, 1, 0};
constexpr BlockCombination d{0, 0, 0, 0, 0, 1};

// Table 4.3.2, 0-based.
constexpr std::array<QuadraticInvariant, 17> table{{
    {true, r, d},         // π1 = r·d
    {true, e2, d},        // π2 = e_2·d
    {true, e3, d},        // π3 = e_3·d
    {true, e4, d},        // π4 = e_4·d
    {false, none, none},  // π5 = ξ¹
    {false, none, none},  // π6 = ξ²
    {false, none, none},  // π7 = f_3
    {true, d, d},         // π8 = d·d
    {true, e2, r},        // π9 = e_2·r
    {true, e3, r},        // π10 = e_3·r
    {true, e4, r},        // π11 = e_4·r
    {true, e2, e2},       // π12 = e_2·e_2
    {true, e2, e3},       // π13 = e_2·e_3
    {true, e2, e4},       // π14 = e_2·e_4
    {true, e3, e3},       // π15 = e_3·e_3
    {true, e3, e4},       // π16 = e_3·e_4
    {true, e4, e4},       // π17 = e_4·e_4
}};

Eigen::Vector3d combine(const BlockCombination& c, const Vector20& q) {
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (int j = 0; j < 6; ++j)
    if (c[j] != 0) v += c[j] * q.segment<3>(3 * j);
  return v;
}
}  // namespace

Vector20 mixed_coordinates(const Eigen::Vector3d& slave, const SegmentNodes& nodes,
                           const Eigen::Vector3d& dir, const Eigen::Vector2d& xi) {
  Vector20 q;
  q.head<15>() = element_vector(slave, nodes);
  q.segment<3>(MixedLayout::director) = dir;
  q.segment<2>(MixedLayout::xi) = xi;
  return q;
}

Vector17 invariants(const Vector20& q, double f3) {
  Vector17 pi;
  for (int k = 0; k < 17; ++k)
    pi[k] = table[k].quadratic ? combine(table[k].a, q).dot(combine(table[k].b, q)) : 0.0;  // table 4.3.2
  pi[4] = q[MixedLayout::xi];                                                               // π5
  pi[5] = q[MixedLayout::xi + 1];                                                           // π6
  pi[6] = f3;                                                                               // π7
  return pi;
}

Matrix17x20 invariant_jacobian(const Vector20& q) {
  Matrix17x20 B = Matrix17x20::Zero();
  for (int k = 0; k < 17; ++k) {
    if (!table[k].quadratic) continue;
    const Eigen::Vector3d a = combine(table[k].a, q), b = combine(table[k].b, q);
    for (int j = 0; j < 6; ++j)
      B.block<1, 3>(k, 3 * j) = (table[k].a[j] * b + table[k].b[j] * a).transpose();  // §4.3.4: P_aᵀb + P_bᵀa
  }
  B(4, MixedLayout::xi) = 1;      // §4.3.4: π5
  B(5, MixedLayout::xi + 1) = 1;  // §4.3.4: π6
  return B;
}

Matrix20 invariant_hessian_contraction(const Vector17& mu) {
  Eigen::Matrix<double, 6, 6> C = Eigen::Matrix<double, 6, 6>::Zero();
  for (int k = 0; k < 17; ++k) {
    if (!table[k].quadratic) continue;
    const Eigen::Map<const Eigen::Matrix<double, 6, 1>> a(table[k].a.data()), b(table[k].b.data());
    C += mu[k] * (a * b.transpose() + b * a.transpose());  // §4.3.4: A_k = P_aᵀP_b + P_bᵀP_a
  }
  Matrix20 A = Matrix20::Zero();
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) A.block<3, 3>(3 * i, 3 * j).diagonal().setConstant(C(i, j));
  return A;
}

}  // namespace stoss::contact
