#include "core/contact/mortar/pair_derivatives.hpp"

#include "core/contact/mortar/second_order.hpp"

namespace stoss::contact::mortar {
namespace {

using Dual = Eigen::AutoDiffScalar<Eigen::Matrix<double, 24, 1>>;
using Second = SecondOrder<24>;

/// Derivatives of a dual that a branch left constant come back empty: read as zero.
Eigen::Matrix<double, 1, 24> gradient_of(const Dual& x) {
  if (x.derivatives().size() != 24) return Eigen::Matrix<double, 1, 24>::Zero();
  return x.derivatives().transpose();
}
Eigen::Matrix<double, 1, 24> gradient_of(const Second& x) {
  return x.gradient().transpose();
}

Dual variable(double value, int index, const Dual*) {
  return Dual(value, 24, index);
}
Second variable(double value, int index, const Second*) {
  return Second::variable(value, index);
}

/// The 24 coordinates as variables: slave nodes 1–4 then master nodes 1–4, 3 each.
template <class T>
void seed(const SegmentNodes& slave, const SegmentNodes& master, QuadNodes<T>& s, QuadNodes<T>& m) {
  for (int K = 0; K < 4; ++K)
    for (int i = 0; i < 3; ++i) {
      s[K][i] = variable(slave(K, i), 3 * K + i, static_cast<const T*>(nullptr));
      m[K][i] = variable(master(K, i), 12 + 3 * K + i, static_cast<const T*>(nullptr));
    }
}

template <class T>
FacePairIntegrals<T> integrals(const SegmentNodes& slave, const SegmentNodes& master, Multipliers kind,
                               const Eigen::Vector4d& offset, PairGaps& out) {
  QuadNodes<T> s, m;
  seed(slave, master, s, m);
  const FacePairIntegrals<T> r = face_pair_integrals<T>(s, m, kind, Integrals::gaps, offset);
  out.area = value_of(r.area);
  out.basis_integral = r.basis_integral;
  out.facing_weight = r.facing_weight;
  for (int j = 0; j < 4; ++j) {
    out.gap[j] = value_of(r.gap[j]);
    out.weight[j] = r.weight[j];
    out.gradient.row(j) = gradient_of(r.gap[j]);  // (4.80)
  }
  return r;
}

}  // namespace

PairGaps pair_gaps(const SegmentNodes& slave, const SegmentNodes& master, Multipliers kind,
                   const Eigen::Vector4d& offset) {
  PairGaps out;
  integrals<Dual>(slave, master, kind, offset, out);
  return out;
}

PairGaps pair_gaps(const SegmentNodes& slave, const SegmentNodes& master, Multipliers kind,
                   const Eigen::Vector4d& lambda, Matrix24& weighted_hessian, const Eigen::Vector4d& offset) {
  PairGaps out;
  const FacePairIntegrals<Second> r = integrals<Second>(slave, master, kind, offset, out);
  Second::Hessian sum = Second::Hessian::Zero();
  for (int j = 0; j < 4; ++j) sum += lambda[j] * r.gap[j].packed_hessian();  // (4.81)
  for (int a = 0, k = 0; a < 24; ++a)
    for (int b = a; b < 24; ++b, ++k) weighted_hessian(a, b) = weighted_hessian(b, a) = sum[k];
  return out;
}

}  // namespace stoss::contact::mortar
