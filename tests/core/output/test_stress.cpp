// Element stresses written into the frames: Cauchy stress of St. Venant–Kirchhoff from the frame's
// positions, checked against closed forms.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "core/output/stress.hpp"
#include "output_test_utils.hpp"

namespace stoss::output {
namespace {

// λ = μ = 4000 (E = 1e4, ν = 0.25) in the tiny model.
constexpr double lambda = 4000, mu = 4000;

TEST(ElementStress, UniaxialStretchMatchesTheClosedForm) {
  const model::Model m = testing::tiny_model();
  const ElementStress stress(m);
  ASSERT_TRUE(stress.available());
  const double e = 0.1;
  Eigen::VectorXd x = m.mesh.reference_positions();
  for (int n = 0; n < m.mesh.node_count(); ++n) x[3 * n] *= 1 + e;  // F = diag(1 + e, 1, 1)
  std::vector<double> sigma, vm;
  stress.compute(x, sigma, vm);
  const double a = ((1 + e) * (1 + e) - 1) / 2;  // E11
  const double s11 = (1 + e) * (lambda + 2 * mu) * a, s22 = lambda * a / (1 + e);
  for (int el = 0; el < 2; ++el) {
    EXPECT_NEAR(sigma[6 * el + 0], s11, 1e-9 * s11);  // xx
    EXPECT_NEAR(sigma[6 * el + 3], s22, 1e-9 * s11);  // yy
    EXPECT_NEAR(sigma[6 * el + 5], s22, 1e-9 * s11);  // zz
    for (int c : {1, 2, 4}) EXPECT_NEAR(sigma[6 * el + c], 0, 1e-9 * s11);
    EXPECT_NEAR(vm[el], s11 - s22, 1e-9 * s11);
  }
}

TEST(ElementStress, RigidMotionIsStressFree) {
  const model::Model m = testing::tiny_model();
  const ElementStress stress(m);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Eigen::VectorXd x(3 * m.mesh.node_count());
  for (int n = 0; n < m.mesh.node_count(); ++n) x.segment<3>(3 * n) = R * m.mesh.nodes[n] + Eigen::Vector3d(5, -2, 1);
  std::vector<double> sigma, vm;
  stress.compute(x, sigma, vm);
  for (double s : sigma) EXPECT_NEAR(s, 0, 1e-9);
  for (double v : vm) EXPECT_NEAR(v, 0, 1e-9);
}

TEST(ElementStress, UnavailableWithoutMaterials) {
  model::Model m = testing::tiny_model();
  m.bodies.clear();
  EXPECT_FALSE(ElementStress(m).available());
}

}  // namespace
}  // namespace stoss::output
