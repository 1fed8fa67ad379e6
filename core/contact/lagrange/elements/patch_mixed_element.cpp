#include "core/contact/lagrange/elements/patch_mixed_element.hpp"

#include <array>

namespace stoss::contact {
namespace {

/// A square matrix of T, row-major.
template <class T>
struct Square {
  int n = 0;
  std::vector<T> a;
  explicit Square(int size) : n(size), a(size * size, T(0.0)) {}
  T& operator()(int i, int j) { return a[i * n + j]; }
  void put_symmetric(int i, int j, const T& v) {
    (*this)(i, j) += v;
    if (i != j) (*this)(j, i) += v;
  }
};

/// S_k of (3.2) for k = 0 … 5 in the generator order (r, e_1 … e_{M−1}, d): linear entries from
/// `lin`, the Π entries of the two CPP rows from the bilinear form −¼ s (p_{,α} ⊗ q + q_{,α} ⊗ p +
/// transposes) (s = 1, p = q = values: the matrices themselves; s = 2, p = divided differences, q = means:
/// their divided differences by the product rule), constant entries scaled by `constants`.
template <class T>
std::array<Square<T>, 6> constraint_matrices(int M, const BasisValues<T>& lin, const BasisValues<T>& p,
                                             const BasisValues<T>& q, double s, double constants) {
  std::array<Square<T>, 6> S{Square<T>(M + 1), Square<T>(M + 1), Square<T>(M + 1),
                             Square<T>(M + 1), Square<T>(M + 1), Square<T>(M + 1)};
  const int d = M;
  S[0].put_symmetric(0, d, T(0.5 * constants));  // (3.2) g_1: r·d
  S[3].put_symmetric(d, d, T(0.5 * constants));  // (3.2) g_4: ½ d·d
  for (int i = 1; i < M; ++i) {
    S[0].put_symmetric(i, d, T(-0.5) * lin.N[i]);  // (3.2) g_1: −N̂_i e_i·d
    S[1].put_symmetric(i, d, T(0.5) * lin.N1[i]);  // (3.2) g_2: N̂_{i,1} e_i·d
    S[2].put_symmetric(i, d, T(0.5) * lin.N2[i]);  // (3.2) g_3
    S[4].put_symmetric(i, 0, T(0.5) * lin.N1[i]);  // (3.2) g_5: N̂_{i,1} e_i·r
    S[5].put_symmetric(i, 0, T(0.5) * lin.N2[i]);  // (3.2) g_6
    for (int j = 1; j < M; ++j) {
      const T w = T(-0.25 * s);  // (3.2) g_5, g_6: −N̂_{i,α} N̂_j e_i·e_j, symmetrised
      S[4](i, j) += w * (p.N1[i] * q.N[j] + q.N1[i] * p.N[j] + p.N1[j] * q.N[i] + q.N1[j] * p.N[i]);
      S[5](i, j) += w * (p.N2[i] * q.N[j] + q.N2[i] * p.N[j] + p.N2[j] * q.N[i] + q.N2[j] * p.N[i]);
    }
  }
  return S;
}

template <class T>
BasisValues<T> mean(const BasisValues<T>& a, const BasisValues<T>& b) {
  BasisValues<T> m = a;
  for (size_t K = 0; K < a.N.size(); ++K) {
    m.N[K] = T(0.5) * (a.N[K] + b.N[K]);
    m.N1[K] = T(0.5) * (a.N1[K] + b.N1[K]);
    m.N2[K] = T(0.5) * (a.N2[K] + b.N2[K]);
  }
  return m;
}

/// A matrix and its derivatives with respect to ξ_{n+1}.
struct Jet {
  Eigen::MatrixXd v, d[2];
};

Jet to_jet(const Square<Dual>& s) {
  Jet j{Eigen::MatrixXd(s.n, s.n), {Eigen::MatrixXd(s.n, s.n), Eigen::MatrixXd(s.n, s.n)}};
  for (int r = 0; r < s.n; ++r)
    for (int c = 0; c < s.n; ++c) {
      const Dual& x = s.a[r * s.n + c];
      j.v(r, c) = x.v;
      j.d[0](r, c) = x.g[0];
      j.d[1](r, c) = x.g[1];
    }
  return j;
}

Eigen::MatrixXd to_matrix(const Square<double>& s) {
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(s.a.data(),
                                                                                                  s.n, s.n);
}

std::array<Eigen::MatrixXd, 6> matrices_at(const TensorPatch& p, const Eigen::Vector2d& xi) {
  const BasisValues<double> v = patch_values(p, xi[0], xi[1]);
  const auto S = constraint_matrices(p.size(), v, v, v, 1, 1);
  std::array<Eigen::MatrixXd, 6> out;
  for (int k = 0; k < 6; ++k) out[k] = to_matrix(S[k]);
  return out;
}

/// S_k(ξ_b) with its ξ_b derivatives.
std::array<Jet, 6> matrices_with_slopes(const TensorPatch& p, const Dual& b1, const Dual& b2) {
  const BasisValues<Dual> v = patch_values(p, b1, b2);
  const auto S = constraint_matrices(p.size(), v, v, v, 1, 1);
  std::array<Jet, 6> out;
  for (int k = 0; k < 6; ++k) out[k] = to_jet(S[k]);
  return out;
}

/// ∇̄_α S_k (3.4): the mean of the divided differences in direction α at the other coordinate of
/// ξ_a and of ξ_b, with their ξ_b derivatives. Indexed [k][α].
std::array<std::array<Jet, 2>, 6> divided_matrices(const TensorPatch& p, const Eigen::Vector2d& a,
                                                   const Dual& b1, const Dual& b2) {
  const int M = p.size();
  const Dual a1(a[0]), a2(a[1]);
  const Dual lo[2] = {a1, a2}, hi[2] = {b1, b2};
  std::array<std::array<Jet, 2>, 6> out;
  for (int alpha = 0; alpha < 2; ++alpha) {
    const int other = 1 - alpha;
    std::array<Square<Dual>, 6> sum{Square<Dual>(M + 1), Square<Dual>(M + 1), Square<Dual>(M + 1),
                                    Square<Dual>(M + 1), Square<Dual>(M + 1), Square<Dual>(M + 1)};
    for (const Dual& c : {lo[other], hi[other]}) {
      const BasisValues<Dual> dd = patch_divided(p, alpha, lo[alpha], hi[alpha], c);
      const BasisValues<Dual> at_lo = alpha == 0 ? patch_values(p, lo[0], c) : patch_values(p, c, lo[1]);
      const BasisValues<Dual> at_hi = alpha == 0 ? patch_values(p, hi[0], c) : patch_values(p, c, hi[1]);
      const auto S = constraint_matrices(M, dd, dd, mean(at_lo, at_hi), 2, 0);
      for (int k = 0; k < 6; ++k)
        for (size_t e = 0; e < S[k].a.size(); ++e) sum[k].a[e] += Dual(0.5) * S[k].a[e];
    }
    for (int k = 0; k < 6; ++k) out[k][alpha] = to_jet(sum[k]);
  }
  return out;
}

/// U = [r; e_1 … e_{M−1}; d] ((M+1) × 3).
Eigen::MatrixXd generators(const PatchMixedState& s) {
  const int M = static_cast<int>(s.master.rows());
  Eigen::MatrixXd U(M + 1, 3);
  U.row(0) = (s.slave - s.master.row(0).transpose()).transpose();
  for (int i = 1; i < M; ++i) U.row(i) = s.master.row(i) - s.master.row(0);
  U.row(M) = s.d.transpose();
  return U;
}

/// T with U = T [x_s; y_0 … y_{M−1}; d] row-wise ((M+1) × (M+2)).
Eigen::MatrixXd generator_map(int M) {
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(M + 1, M + 2);
  T(0, 0) = 1;
  T(0, 1) = -1;
  for (int i = 1; i < M; ++i) T(i, 1 + i) = 1, T(i, 1) = -1;
  T(M, M + 1) = 1;
  return T;
}

double contract(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  return A.cwiseProduct(B).sum();
}

constexpr double offsets(int k, double f3) {
  return k == 0 ? -f3 : k == 3 ? -0.5 : 0.0;
}  // κ_k (3.2)

/// Writes the node-level rows (M+2 nodes × 3) of a generator-level quantity G_U into a vector.
void put_nodes(const Eigen::MatrixXd& T, const Eigen::MatrixXd& G_U, Eigen::Ref<Eigen::VectorXd> out) {
  const Eigen::MatrixXd nodes = T.transpose() * G_U;
  for (int c = 0; c < nodes.rows(); ++c) out.segment<3>(3 * c) = nodes.row(c).transpose();
}

}  // namespace

Vector6 patch_constraints(const TensorPatch& p, const PatchMixedState& s, double f3) {
  const Eigen::MatrixXd U = generators(s);
  const Eigen::MatrixXd G = U * U.transpose();
  const auto S = matrices_at(p, s.xi);
  Vector6 g;
  for (int k = 0; k < 6; ++k) g[k] = contract(S[k], G) + offsets(k, f3);  // (3.2)
  return g;
}

PatchMixedResult patch_mixed_element(const TensorPatch& p, const PatchMixedState& at_n,
                                     const PatchMixedState& at_1, const Vector6& lambda, double f3,
                                     double h) {
  const int M = p.size(), nodes = M + 2, xi = 3 * nodes, lam = xi + 2;
  const Eigen::MatrixXd T = generator_map(M);
  const Eigen::MatrixXd Ua = generators(at_n), Ub = generators(at_1), Um = 0.5 * (Ua + Ub);
  const Eigen::MatrixXd Ga = Ua * Ua.transpose(), Gb = Ub * Ub.transpose(), Gm = 0.5 * (Ga + Gb);
  const Dual b1(at_1.xi[0], Eigen::Vector2d(1, 0)), b2(at_1.xi[1], Eigen::Vector2d(0, 1));
  const auto Sa = matrices_at(p, at_n.xi);
  const auto Sb = matrices_with_slopes(p, b1, b2);
  const auto DG = divided_matrices(p, at_n.xi, b1, b2);

  Eigen::MatrixXd S_mean_lambda = Eigen::MatrixXd::Zero(M + 1, M + 1), dSb_lambda[2], DG_lambda[2];
  for (int a = 0; a < 2; ++a) dSb_lambda[a] = DG_lambda[a] = S_mean_lambda;
  for (int k = 0; k < 6; ++k) {
    S_mean_lambda += lambda[k] * 0.5 * (Sa[k] + Sb[k].v);  // Σ λ_k ∇̄_G g_k (3.3)
    for (int a = 0; a < 2; ++a) {
      dSb_lambda[a] += lambda[k] * Sb[k].d[a];
      DG_lambda[a] += lambda[k] * DG[k][a].v;
    }
  }

  PatchMixedResult out;
  out.Rq = Eigen::VectorXd::Zero(lam);
  out.K = Eigen::MatrixXd::Zero(lam + 6, lam + 6);
  put_nodes(T, 2 * h * S_mean_lambda * Um, out.Rq.head(xi));                    // (3.5) h B_xᵀμ, B_dᵀμ
  for (int a = 0; a < 2; ++a) out.Rq[xi + a] = h * contract(Gm, DG_lambda[a]);  // (3.5) R_ξ
  for (int k = 0; k < 6; ++k) {
    out.Rl[k] = contract(Sb[k].v, Gb) + offsets(k, f3);  // (3.5) g(π_{n+1})
    out.g_n[k] = contract(Sa[k], Ga) + offsets(k, f3);   // (4.11)
  }

  const Eigen::MatrixXd K_nodes = T.transpose() * (h * S_mean_lambda) * T;  // ∂(h 2S̃U_m)/∂U_{n+1}
  for (int r = 0; r < nodes; ++r)
    for (int c = 0; c < nodes; ++c) out.K.block<3, 3>(3 * r, 3 * c).diagonal().setConstant(K_nodes(r, c));
  for (int a = 0; a < 2; ++a) {
    put_nodes(T, h * dSb_lambda[a] * Um, out.K.col(xi + a).head(xi));  // ∂R_x/∂ξ_{n+1}
    Eigen::VectorXd row(xi);
    put_nodes(T, h * DG_lambda[a] * Ub, row);  // ∂R_ξ/∂U_{n+1}
    out.K.row(xi + a).head(xi) = row.transpose();
    for (int b = 0; b < 2; ++b) {
      double s = 0;
      for (int k = 0; k < 6; ++k) s += lambda[k] * contract(Gm, DG[k][a].d[b]);
      out.K(xi + a, xi + b) = h * s;
    }
  }
  for (int k = 0; k < 6; ++k) {
    put_nodes(T, 2 * h * 0.5 * (Sa[k] + Sb[k].v) * Um, out.K.col(lam + k).head(xi));  // ∂R_x/∂λ_k
    for (int a = 0; a < 2; ++a) out.K(xi + a, lam + k) = h * contract(Gm, DG[k][a].v);
    Eigen::VectorXd row(xi);
    put_nodes(T, 2 * Sb[k].v * Ub, row);  // ∂g_k/∂U_{n+1}
    out.K.row(lam + k).head(xi) = row.transpose();
    for (int a = 0; a < 2; ++a) out.K(lam + k, xi + a) = contract(Sb[k].d[a], Gb);
  }
  return out;
}

}  // namespace stoss::contact
