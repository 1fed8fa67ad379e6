// Element stresses of the result frames (docs/results.md "/frames"): the volume-averaged Cauchy stress of
// the hex8 kernel and its von Mises value, checked against closed forms.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "core/fem/assembly.hpp"
#include "core/fem/element.hpp"
#include "core/fem/saint_venant_kirchhoff.hpp"

namespace stoss::fem {
namespace {

// E = 1e4, ν = 0.25: λ = μ = 4000.
constexpr double lambda = 4000, mu = 4000;

/// A brick [0,2]×[0,1]×[0,0.5] (det J0 ≠ 1), its nodes as rows in VTK_HEXAHEDRON order.
Matrix83 brick() {
  Matrix83 X;
  X << 0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0, 0, 0, 0.5, 2, 0, 0.5, 2, 1, 0.5, 0, 1, 0.5;
  return X;
}

const SaintVenantKirchhoff material(1e4, 0.25);

// F = diag(1 + e, 1, 1): S = λ tr(E) 1 + 2μ E with E11 = ((1+e)² − 1)/2, σ = F S Fᵀ / J.
TEST(CauchyStress, UniaxialStretchMatchesTheClosedForm) {
  const ElementGeometry g = precompute_geometry(brick());
  const double e = 0.1;
  Matrix83 x = brick();
  x.col(0) *= 1 + e;
  const Eigen::Matrix3d sigma = average_cauchy_stress(g, material, x);
  const double a = ((1 + e) * (1 + e) - 1) / 2;
  const double s11 = (1 + e) * (lambda + 2 * mu) * a, s22 = lambda * a / (1 + e);
  EXPECT_NEAR(sigma(0, 0), s11, 1e-9 * s11);
  EXPECT_NEAR(sigma(1, 1), s22, 1e-9 * s11);
  EXPECT_NEAR(sigma(2, 2), s22, 1e-9 * s11);
  for (auto [i, j] : {std::pair{0, 1}, {0, 2}, {1, 2}}) {
    EXPECT_NEAR(sigma(i, j), 0, 1e-9 * s11);
    EXPECT_EQ(sigma(i, j), sigma(j, i));
  }
  EXPECT_NEAR(von_mises(sigma), s11 - s22, 1e-9 * s11);  // uniaxial-like: |σ11 − σ22|
}

TEST(CauchyStress, RigidMotionIsStressFree) {
  const ElementGeometry g = precompute_geometry(brick());
  const Eigen::Matrix3d R = Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Matrix83 x;
  for (int I = 0; I < 8; ++I)
    x.row(I) = (R * brick().row(I).transpose() + Eigen::Vector3d(5, -2, 1)).transpose();
  const Eigen::Matrix3d sigma = average_cauchy_stress(g, material, x);
  EXPECT_LT(sigma.cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT(von_mises(sigma), 1e-9);
}

// A pure pressure has no deviator; a pure shear τ has von Mises √3 τ.
TEST(CauchyStress, VonMisesOfPressureAndShear) {
  EXPECT_NEAR(von_mises(-7.0 * Eigen::Matrix3d::Identity()), 0, 1e-12);
  Eigen::Matrix3d shear = Eigen::Matrix3d::Zero();
  shear(0, 1) = shear(1, 0) = 2.0;
  EXPECT_NEAR(von_mises(shear), 2.0 * std::sqrt(3.0), 1e-12);
}

// The elasticity term gives each element's σ in Tensor6 order (xx, xy, xz, yy, yz, zz) and its von Mises.
TEST(CauchyStress, ElasticityTermListsEveryElementInTensor6Order) {
  mesh::Mesh m;
  mesh::BodyMesh body;
  const Matrix83 X = brick();
  for (int I = 0; I < 8; ++I) body.nodes.emplace_back(X.row(I).transpose());
  body.hex8.push_back({0, 1, 2, 3, 4, 5, 6, 7});
  m.add_body("brick", body);
  const auto shared = std::make_shared<SaintVenantKirchhoff>(1e4, 0.25);
  const ElasticityTerm term(m, precompute_mesh(m), {shared});
  Eigen::VectorXd x = m.reference_positions();
  for (int n = 0; n < 8; ++n) x[3 * n + 1] += 0.2 * x[3 * n];  // a shear x_y += 0.2 X_x
  Eigen::VectorXd cauchy, vm;
  term.element_stresses(x, cauchy, vm);
  ASSERT_EQ(cauchy.size(), 6);
  ASSERT_EQ(vm.size(), 1);
  const Eigen::Matrix3d sigma = average_cauchy_stress(precompute_geometry(X), *shared, gather(m.hex8[0], x));
  const double expected[6] = {sigma(0, 0), sigma(0, 1), sigma(0, 2), sigma(1, 1), sigma(1, 2), sigma(2, 2)};
  for (int c = 0; c < 6; ++c) EXPECT_EQ(cauchy[c], expected[c]) << c;
  EXPECT_GT(std::abs(cauchy[1]), 1.0) << "the shear shows in xy";
  EXPECT_EQ(vm[0], von_mises(sigma));
}

}  // namespace
}  // namespace stoss::fem
