#include "core/output/stress.hpp"

#include <Eigen/LU>
#include <cmath>

namespace stoss::output {

namespace {

/// Corner signs (ξ_I, η_I, ζ_I) of the VTK_HEXAHEDRON nodes.
constexpr double corner[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                 {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

/// ∂N_I/∂ξ at a point of the reference cube, N_I = ⅛(1 + ξ ξ_I)(1 + η η_I)(1 + ζ ζ_I).
Eigen::Matrix<double, 8, 3> local_gradients(const Eigen::Vector3d& xi) {
  Eigen::Matrix<double, 8, 3> d;
  for (int I = 0; I < 8; ++I) {
    const double a = 1 + xi[0] * corner[I][0], b = 1 + xi[1] * corner[I][1], c = 1 + xi[2] * corner[I][2];
    d(I, 0) = corner[I][0] * b * c / 8;
    d(I, 1) = a * corner[I][1] * c / 8;
    d(I, 2) = a * b * corner[I][2] / 8;
  }
  return d;
}

}  // namespace

ElementStress::ElementStress(const model::Model& model) {
  const mesh::Mesh& m = model.mesh;
  if (model.bodies.size() != m.bodies.size() || m.hex8.empty()) return;
  const double g = 1 / std::sqrt(3.0);
  hex8_ = m.hex8;
  gauss_.resize(m.hex8.size());
  std::vector<std::shared_ptr<const fem::Material>> body_material;
  for (const model::BodySpec& body : model.bodies) body_material.push_back(fem::make_material(body.material));
  for (size_t e = 0; e < m.hex8.size(); ++e) {
    material_.push_back(body_material[m.element_body[e]]);
    Eigen::Matrix<double, 8, 3> X;
    for (int I = 0; I < 8; ++I) X.row(I) = m.nodes[m.hex8[e][I]].transpose();
    int k = 0;
    for (double z : {-g, g})
      for (double y : {-g, g})
        for (double x : {-g, g}) {
          const Eigen::Matrix<double, 8, 3> dN = local_gradients({x, y, z});
          const Eigen::Matrix3d J0 = X.transpose() * dN;  // ∂X/∂ξ
          gauss_[e][k].wJ0 = J0.determinant();
          gauss_[e][k].dN_dX = dN * J0.inverse();
          ++k;
        }
  }
  available_ = true;
}

void ElementStress::compute(const Eigen::VectorXd& positions, std::vector<double>& cauchy,
                            std::vector<double>& von_mises) const {
  cauchy.assign(6 * hex8_.size(), 0.0);
  von_mises.assign(hex8_.size(), 0.0);
  for (size_t e = 0; e < hex8_.size(); ++e) {
    Eigen::Matrix<double, 8, 3> x;
    for (int I = 0; I < 8; ++I) x.row(I) = positions.segment<3>(3 * hex8_[e][I]).transpose();
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    double volume = 0;
    for (const GaussPoint& gp : gauss_[e]) {
      const Eigen::Matrix3d F = x.transpose() * gp.dN_dX;
      const double J = F.determinant();
      const Eigen::Matrix3d strain = 0.5 * (F.transpose() * F - Eigen::Matrix3d::Identity());
      const Eigen::Matrix3d S = material_[e]->stress(strain);
      const double w = gp.wJ0 * J;
      sum += w * (F * S * F.transpose()) / J;
      volume += w;
    }
    const Eigen::Matrix3d sigma = sum / volume;
    const double values[6] = {sigma(0, 0), sigma(0, 1), sigma(0, 2), sigma(1, 1), sigma(1, 2), sigma(2, 2)};
    std::copy(values, values + 6, cauchy.begin() + 6 * static_cast<long>(e));
    const Eigen::Matrix3d s = sigma - sigma.trace() / 3 * Eigen::Matrix3d::Identity();
    von_mises[e] = std::sqrt(1.5 * (s.array() * s.array()).sum());
  }
}

}  // namespace stoss::output
