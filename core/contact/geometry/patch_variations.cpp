#include "core/contact/geometry/patch_variations.hpp"

#include <Eigen/LU>
#include <array>

namespace stoss::contact {
namespace {

/// [a; −c_K a] over the element vector, for node values c.
Eigen::RowVectorXd slave_minus_master(const Eigen::Vector3d& a, const Eigen::VectorXd& c) {
  Eigen::RowVectorXd row(3 + 3 * c.size());
  row.head<3>() = a.transpose();
  for (Eigen::Index K = 0; K < c.size(); ++K) row.segment<3>(3 + 3 * K) = -c[K] * a.transpose();
  return row;
}

/// [0; c_K a] over the element vector.
Eigen::RowVectorXd master_only(const Eigen::Vector3d& a, const Eigen::VectorXd& c) {
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(3 + 3 * c.size());
  for (Eigen::Index K = 0; K < c.size(); ++K) row.segment<3>(3 + 3 * K) = c[K] * a.transpose();
  return row;
}

}  // namespace

namespace {

/// y_{,αβ} of a frame as [α][β].
struct Curvature {
  Eigen::Vector3d y2[2][2];
  explicit Curvature(const PatchFrame& f) : y2{{f.y11, f.y12}, {f.y12, f.y22}} {}
};

/// A_αβ = m_αβ − g_N n·y_{,αβ} (3.4) at the CPP, every curvature term.
Eigen::Matrix2d projection_matrix_at(const PatchFrame& f, const Curvature& k, double gap) {
  Eigen::Matrix2d A = f.metric;
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 2; ++c) A(a, c) -= gap * f.normal.dot(k.y2[a][c]);
  return A;
}

}  // namespace

PatchPoint patch_point(const TensorPatch& p, const Eigen::VectorXd& x, const Eigen::Vector2d& xi) {
  const BasisValues<double> b = patch_values(p, xi[0], xi[1]);
  PatchPoint at;
  at.curvatures = patch_curvatures(p, xi);
  at.frame = patch_frame(p, x, xi, b, at.curvatures);
  at.N = as_vector(b.N);
  at.dN[0] = as_vector(b.N1);
  at.dN[1] = as_vector(b.N2);
  return at;
}

Eigen::VectorXd patch_gap_gradient(const PatchPoint& at) {
  return slave_minus_master(at.frame.normal, at.N).transpose();  // (3.6)
}

Eigen::VectorXd patch_gap_gradient(const TensorPatch& p, const Eigen::VectorXd& x,
                                   const Eigen::Vector2d& xi) {
  return patch_gap_gradient(patch_point(p, x, xi));
}

Eigen::MatrixXd patch_xi_gradient(const PatchPoint& at, double gap) {
  const PatchFrame& f = at.frame;
  const Eigen::Vector3d tau[2] = {f.tau1, f.tau2};
  Eigen::MatrixXd TN(2, 3 + 3 * at.N.size());  // T_β + g_N N̄_β (3.7)
  for (int c = 0; c < 2; ++c)
    TN.row(c) = slave_minus_master(tau[c], at.N) + gap * master_only(f.normal, at.dN[c]);
  return projection_matrix_at(f, Curvature(f), gap).inverse() * TN;
}

PatchGapVariations patch_gap_variations(const TensorPatch& p, const Eigen::VectorXd& x,
                                        const Eigen::Vector2d& xi, double gap) {
  return patch_gap_variations(patch_point(p, x, xi), gap);
}

PatchGapVariations patch_gap_variations(const PatchPoint& at, double gap) {
  const PatchFrame& f = at.frame;
  const Eigen::VectorXd& N = at.N;
  const Eigen::VectorXd(&dN)[2] = at.dN;
  const Eigen::Vector3d tau[2] = {f.tau1, f.tau2};
  const Curvature k(f);
  const Eigen::Index n = 3 + 3 * N.size();
  PatchGapVariations v;
  v.D = patch_xi_gradient(at, gap);  // D_α (3.7)
  const Eigen::MatrixXd& D = v.D;
  Eigen::MatrixXd n_dtau(2, n);  // n·∂τ_α/∂x = [0; N_{K,α} n] + Σ_β (n·y_{,αβ}) D_β (3.8)
  for (int a = 0; a < 2; ++a)
    n_dtau.row(a) = master_only(f.normal, dN[a]) + f.normal.dot(k.y2[a][0]) * D.row(0) +
                    f.normal.dot(k.y2[a][1]) * D.row(1);
  v.dn = Eigen::MatrixXd::Zero(3, n);  // ∂n/∂x = −m^{αβ} τ_β ⊗ (n·∂τ_α/∂x) (3.8)
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 2; ++c) v.dn -= f.metric_inv(a, c) * tau[c] * n_dtau.row(a);
  v.Ns = slave_minus_master(f.normal, N).transpose();  // (3.6)
  v.dNs.resize(n, n);
  v.dNs.topRows<3>() = v.dn;  // (3.9)
  for (Eigen::Index K = 0; K < N.size(); ++K) {
    const Eigen::RowVectorXd dNK = dN[0][K] * D.row(0) + dN[1][K] * D.row(1);  // ∂N_K/∂x = N_{K,α} D_α
    v.dNs.middleRows<3>(3 + 3 * K) = -f.normal * dNK - N[K] * v.dn;            // (3.9)
  }
  return v;
}

std::array<PatchRows3, 2> patch_tangent_gradients(const PatchPoint& at, const Eigen::MatrixXd& D) {
  const Curvature k(at.frame);
  std::array<PatchRows3, 2> dtau;
  for (int a = 0; a < 2; ++a) {
    dtau[a] = k.y2[a][0] * D.row(0) + k.y2[a][1] * D.row(1);  // y_{,αβ} ⊗ D_β (3.8)
    for (Eigen::Index K = 0; K < at.N.size(); ++K)
      dtau[a].middleCols<3>(3 + 3 * K).diagonal().array() += at.dN[a][K];
  }
  return dtau;
}

Eigen::MatrixXd patch_contracted_xi_hessian(const TensorPatch& p, const Eigen::VectorXd& x,
                                            const PatchPoint& at, double gap, const PatchGapVariations& v,
                                            const std::array<PatchRows3, 2>& dtau, const Eigen::Vector2d& t) {
  const PatchFrame& f = at.frame;
  const BasisThirdDerivatives c3 = patch_third_derivatives(p, f.xi);
  const Eigen::VectorXd& N = at.N;
  const Eigen::VectorXd(&dN)[2] = at.dN;
  const BasisCurvatures& c2 = at.curvatures;
  const Eigen::VectorXd* d2N[2][2] = {{&c2.N11, &c2.N12}, {&c2.N12, &c2.N22}};
  // n·y_{,αβγ} by the number of 2s among α, β, γ
  const double n_y3[4] = {
      f.normal.dot(combine_nodes(p, c3.N111, x)), f.normal.dot(combine_nodes(p, c3.N112, x)),
      f.normal.dot(combine_nodes(p, c3.N122, x)), f.normal.dot(combine_nodes(p, c3.N222, x))};
  const Eigen::Vector3d tau[2] = {f.tau1, f.tau2};
  const Curvature k(f);
  const Eigen::MatrixXd& D = v.D;
  const Eigen::Vector2d s = projection_matrix_at(f, k, gap).inverse() * t;  // A symmetric
  const Eigen::Index n = 3 + 3 * N.size();
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  for (int c = 0; c < 2; ++c) {  // Σ_β s_β ∂B_β, B_β = T_β + g_N N̄_β (3.7)
    H.topRows<3>() += s[c] * dtau[c];
    for (Eigen::Index K = 0; K < N.size(); ++K) {
      const Eigen::RowVectorXd dNK = dN[0][K] * D.row(0) + dN[1][K] * D.row(1);                 // ∂N_K
      const Eigen::RowVectorXd dNKc = (*d2N[c][0])[K] * D.row(0) + (*d2N[c][1])[K] * D.row(1);  // ∂N_{K,β}
      H.middleRows<3>(3 + 3 * K) +=
          s[c] * (-N[K] * dtau[c] - tau[c] * dNK + dN[c][K] * f.normal * v.Ns.transpose() +
                  gap * (dN[c][K] * v.dn + f.normal * dNKc));
    }
  }
  for (int c = 0; c < 2; ++c) {  // − Σ_γ D_γ ⊗ Σ_β s_β ∂A_βγ, A_βγ = m_βγ − g_N n·y_{,βγ} (3.4)
    Eigen::RowVectorXd s_dA = Eigen::RowVectorXd::Zero(n);
    for (int a = 0; a < 2; ++a) {
      const Eigen::RowVectorXd dm = tau[a].transpose() * dtau[c] + tau[c].transpose() * dtau[a];
      Eigen::RowVectorXd n_dy2 = master_only(f.normal, *d2N[a][c]);  // n·∂y_{,αγ}/∂x
      for (int d = 0; d < 2; ++d) n_dy2 += n_y3[a + c + d] * D.row(d);
      const Eigen::RowVectorXd dcurv =
          f.normal.dot(k.y2[a][c]) * v.Ns.transpose() + gap * (k.y2[a][c].transpose() * v.dn + n_dy2);
      s_dA += s[a] * (dm - dcurv);
    }
    H -= D.row(c).transpose() * s_dA;
  }
  return H;
}

}  // namespace stoss::contact
