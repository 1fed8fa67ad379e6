#include "core/contact/mortar/pair_derivatives.hpp"

namespace stoss::contact::mortar {
namespace {

using Inner = Eigen::AutoDiffScalar<Eigen::Matrix<double, 24, 1>>;
using Outer = Eigen::AutoDiffScalar<Eigen::Matrix<Inner, 24, 1>>;

template <class T>
void seed(const SegmentNodes& slave, const SegmentNodes& master, QuadNodes<T>& s, QuadNodes<T>& m);

template <>
void seed<Inner>(const SegmentNodes& slave, const SegmentNodes& master, QuadNodes<Inner>& s,
                 QuadNodes<Inner>& m) {
  for (int K = 0; K < 4; ++K)
    for (int i = 0; i < 3; ++i) {
      s[K][i] = Inner(slave(K, i), 24, 3 * K + i);
      m[K][i] = Inner(master(K, i), 24, 12 + 3 * K + i);
    }
}

template <>
void seed<Outer>(const SegmentNodes& slave, const SegmentNodes& master, QuadNodes<Outer>& s,
                 QuadNodes<Outer>& m) {
  const auto variable = [](double value, int index) {
    Outer x(Inner(value, 24, index));
    x.derivatives() = Eigen::Matrix<Inner, 24, 1>::Constant(Inner(0.0));
    x.derivatives()[index] = Inner(1.0);
    return x;
  };
  for (int K = 0; K < 4; ++K)
    for (int i = 0; i < 3; ++i) {
      s[K][i] = variable(slave(K, i), 3 * K + i);
      m[K][i] = variable(master(K, i), 12 + 3 * K + i);
    }
}

/// Derivatives of a dual that a branch left constant come back empty: read as zero.
Eigen::Matrix<double, 1, 24> gradient_of(const Inner& x) {
  if (x.derivatives().size() != 24) return Eigen::Matrix<double, 1, 24>::Zero();
  return x.derivatives().transpose();
}

}  // namespace

PairGaps pair_gaps(const SegmentNodes& slave, const SegmentNodes& master, Multipliers kind) {
  QuadNodes<Inner> s, m;
  seed(slave, master, s, m);
  const FacePairIntegrals<Inner> r = face_pair_integrals<Inner>(s, m, kind);
  PairGaps out;
  out.area = value_of(r.area);
  for (int j = 0; j < 4; ++j) {
    out.gap[j] = value_of(r.gap[j]);
    out.weight[j] = value_of(r.D(j, j));
    out.gradient.row(j) = gradient_of(r.gap[j]);  // (4.80)
  }
  return out;
}

PairGaps pair_gaps(const SegmentNodes& slave, const SegmentNodes& master, Multipliers kind,
                   const Eigen::Vector4d& lambda, Matrix24& weighted_hessian) {
  QuadNodes<Outer> s, m;
  seed(slave, master, s, m);
  const FacePairIntegrals<Outer> r = face_pair_integrals<Outer>(s, m, kind);
  PairGaps out;
  out.area = value_of(r.area);
  weighted_hessian.setZero();
  for (int j = 0; j < 4; ++j) {
    out.gap[j] = value_of(r.gap[j]);
    out.weight[j] = value_of(r.D(j, j));
    out.gradient.row(j) = gradient_of(r.gap[j].value());  // (4.80)
    const auto& d = r.gap[j].derivatives();
    if (d.size() != 24) continue;
    for (int a = 0; a < 24; ++a) weighted_hessian.row(a) += lambda[j] * gradient_of(d[a]);  // (4.81)
  }
  return out;
}

}  // namespace stoss::contact::mortar
