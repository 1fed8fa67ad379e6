#pragma once
/// @file A second-order forward number: a value with its gradient and its symmetric Hessian with respect to
/// N variables, fixed size (no heap), the Hessian packed as its upper triangle. It carries Σ_j λ_j ∂²g̃_j/∂x²
/// (docs/theory.md (4.81)) through the mortar integrals at a fraction of nested dual numbers' cost: one
/// product updates N(N+1)/2 Hessian entries, where a dual number of dual numbers updates N² of them, each
/// with its own gradient. Values are the plain double operations, so value_of(x) is what the double code
/// gives.

#include <Eigen/Core>
#include <cmath>

namespace stoss::contact::mortar {

template <int N>
class SecondOrder {
 public:
  static constexpr int packed_size = N * (N + 1) / 2;
  using Gradient = Eigen::Matrix<double, N, 1>;
  using Hessian = Eigen::Matrix<double, packed_size, 1>;  ///< (0,0), (0,1) … (0,N−1), (1,1) … row by row

  /// A constant: zero gradient and Hessian.
  SecondOrder(double value = 0) : value_(value), gradient_(Gradient::Zero()), hessian_(Hessian::Zero()) {}
  /// The variable x_index at `value`: unit gradient, zero Hessian.
  static SecondOrder variable(double value, int index) {
    SecondOrder x(value);
    x.gradient_[index] = 1;
    x.constant_ = false;
    return x;
  }

  double value() const { return value_; }
  const Gradient& gradient() const { return gradient_; }
  const Hessian& packed_hessian() const { return hessian_; }
  /// The full symmetric N × N Hessian.
  Eigen::Matrix<double, N, N> hessian() const {
    Eigen::Matrix<double, N, N> H;
    for (int i = 0, k = 0; i < N; ++i)
      for (int j = i; j < N; ++j, ++k) H(i, j) = H(j, i) = hessian_[k];
    return H;
  }

  // A constant operand (the integrals' weights and the shape functions' ¼, 1 ± ξ) changes the value alone, or
  // scales: the same numbers as the full update, whose terms with its zero derivatives add zeros.
  SecondOrder& operator+=(const SecondOrder& b) {
    value_ += b.value_;
    if (b.constant_) return *this;
    gradient_ += b.gradient_, hessian_ += b.hessian_, constant_ = false;
    return *this;
  }
  SecondOrder& operator-=(const SecondOrder& b) {
    value_ -= b.value_;
    if (b.constant_) return *this;
    gradient_ -= b.gradient_, hessian_ -= b.hessian_, constant_ = false;
    return *this;
  }
  SecondOrder& operator*=(double c) {
    value_ *= c, gradient_ *= c, hessian_ *= c;
    return *this;
  }
  SecondOrder& operator*=(const SecondOrder& b) { return *this = *this * b; }
  SecondOrder& operator/=(const SecondOrder& b) { return *this = *this / b; }
  SecondOrder operator-() const {
    SecondOrder r(*this);
    r *= -1.0;
    return r;
  }

  /// (ab)'' = a b'' + b a'' + a' b'ᵀ + b' a'ᵀ.
  friend SecondOrder operator*(const SecondOrder& a, const SecondOrder& b) {
    if (b.constant_) return scaled(a, a.value_ * b.value_, b.value_);
    if (a.constant_) return scaled(b, a.value_ * b.value_, a.value_);
    SecondOrder r(a.value_ * b.value_, uninitialized);
    r.gradient_ = a.value_ * b.gradient_ + b.value_ * a.gradient_;
    for (int i = 0, k = 0; i < N; ++i)
      for (int j = i; j < N; ++j, ++k)
        r.hessian_[k] = a.value_ * b.hessian_[k] + b.value_ * a.hessian_[k] +
                        a.gradient_[i] * b.gradient_[j] + a.gradient_[j] * b.gradient_[i];
    return r;
  }
  /// q = a / b from a = q b: q' = (a' − q b') / b, q'' = (a'' − q b'' − b' q'ᵀ − q' b'ᵀ) / b.
  friend SecondOrder operator/(const SecondOrder& a, const SecondOrder& b) {
    const double inverse = 1 / b.value_;
    if (b.constant_) return scaled(a, a.value_ / b.value_, inverse);
    SecondOrder q(a.value_ / b.value_, uninitialized);
    q.gradient_ = (a.gradient_ - q.value_ * b.gradient_) * inverse;
    for (int i = 0, k = 0; i < N; ++i)
      for (int j = i; j < N; ++j, ++k)
        q.hessian_[k] = (a.hessian_[k] - q.value_ * b.hessian_[k] - b.gradient_[i] * q.gradient_[j] -
                         q.gradient_[i] * b.gradient_[j]) *
                        inverse;
    return q;
  }
  /// r = √a from a = r²: r' = a' / (2r), r'' = (a'' − 2 r' r'ᵀ) / (2r).
  friend SecondOrder sqrt(const SecondOrder& a) {
    if (a.constant_) return SecondOrder(std::sqrt(a.value_));
    SecondOrder r(std::sqrt(a.value_), uninitialized);
    const double inverse = 0.5 / r.value_;
    r.gradient_ = a.gradient_ * inverse;
    for (int i = 0, k = 0; i < N; ++i)
      for (int j = i; j < N; ++j, ++k)
        r.hessian_[k] = (a.hessian_[k] - 2 * r.gradient_[i] * r.gradient_[j]) * inverse;
    return r;
  }

  friend SecondOrder operator+(SecondOrder a, const SecondOrder& b) { return a += b; }
  friend SecondOrder operator-(SecondOrder a, const SecondOrder& b) { return a -= b; }
  friend SecondOrder operator*(SecondOrder a, double c) { return a *= c; }
  friend SecondOrder operator*(double c, SecondOrder a) { return a *= c; }
  friend SecondOrder operator/(const SecondOrder& a, double c) { return a / SecondOrder(c); }
  friend SecondOrder operator+(SecondOrder a, double c) { return a += SecondOrder(c); }
  friend SecondOrder operator-(SecondOrder a, double c) { return a -= SecondOrder(c); }

 private:
  struct Uninitialized {};
  static constexpr Uninitialized uninitialized{};
  /// A result whose gradient and Hessian the caller writes in full.
  SecondOrder(double value, Uninitialized) : value_(value), constant_(false) {}
  /// a's derivatives times `factor`, with the value `value`.
  static SecondOrder scaled(const SecondOrder& a, double value, double factor) {
    if (a.constant_) return SecondOrder(value);
    SecondOrder r(value, uninitialized);
    r.gradient_ = a.gradient_ * factor;
    r.hessian_ = a.hessian_ * factor;
    return r;
  }

  double value_;
  Gradient gradient_;
  Hessian hessian_;
  bool constant_ = true;  ///< gradient and Hessian are zero (a double made a SecondOrder)
};

}  // namespace stoss::contact::mortar

namespace Eigen {
/// Lets Eigen's fixed-size matrices (dot, cross, norm, the 4 × 4 inverse) hold SecondOrder numbers.
template <int N>
struct NumTraits<stoss::contact::mortar::SecondOrder<N>> : NumTraits<double> {
  using Real = stoss::contact::mortar::SecondOrder<N>;
  using NonInteger = Real;
  using Nested = Real;
  using Literal = double;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 1,
    AddCost = N * (N + 3) / 2,
    MulCost = 2 * N * (N + 3)
  };
};
}  // namespace Eigen
