// Materials behind fem::Material against finite differences, the discrete-stress identity (2.6) and
// closed forms (docs/theory.md §1.2, §2.6).
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <random>

#include "core/fem/material.hpp"
#include "core/fem/neo_hookean.hpp"
#include "core/fem/saint_venant_kirchhoff.hpp"

namespace stoss::fem {
namespace {

Eigen::Matrix3d random_strain(std::mt19937& rng, double size) {
  std::uniform_real_distribution<double> u(-size, size);
  Eigen::Matrix3d A;
  for (int i = 0; i < 9; ++i) A(i / 3, i % 3) = u(rng);
  return 0.5 * (A + A.transpose());
}

/// The symmetric direction of Voigt entry k with engineering shears (the columns of voigt_matrix).
Eigen::Matrix3d voigt_direction(int k) {
  static constexpr int row[6] = {0, 1, 2, 1, 0, 0}, col[6] = {0, 1, 2, 2, 2, 1};
  Eigen::Matrix3d d = Eigen::Matrix3d::Zero();
  d(row[k], col[k]) = d(col[k], row[k]) = k < 3 ? 1.0 : 0.5;
  return d;
}

double contraction(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  return A.cwiseProduct(B).sum();
}

class EachMaterial : public ::testing::TestWithParam<std::shared_ptr<const Material>> {
 protected:
  const Material& material = *GetParam();
  std::mt19937 rng{7};
};

INSTANTIATE_TEST_SUITE_P(Materials, EachMaterial,
                         ::testing::Values(make_material({"saint_venant_kirchhoff", 2e3, 0.3, 1}),
                                           make_material({"neo_hookean", 2e3, 0.45, 1})),
                         [](const auto& info) { return info.param->name(); });

TEST_P(EachMaterial, StressIsTheGradientOfTheEnergy) {
  const Eigen::Matrix3d E = random_strain(rng, 0.2);
  const Eigen::Matrix3d S = material.stress(E);
  const double eps = 1e-6;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Eigen::Matrix3d d = Eigen::Matrix3d::Zero();
      d(i, j) += 0.5 * eps;
      d(j, i) += 0.5 * eps;
      const double fd = (material.energy_density(E + d) - material.energy_density(E - d)) / (2 * eps);
      EXPECT_NEAR(S(i, j), fd, 1e-6 * S.norm()) << i << j;
    }
}

TEST_P(EachMaterial, TangentMatchesFiniteDifferencesOfTheStress) {
  const Eigen::Matrix3d E = random_strain(rng, 0.2);
  const Matrix6d D = material.tangent(E);
  const double eps = 1e-6;
  Matrix6d fd;
  for (int k = 0; k < 6; ++k) {
    const Eigen::Matrix3d d = eps * voigt_direction(k);
    fd.col(k) = to_voigt_stress(material.stress(E + d) - material.stress(E - d)) / (2 * eps);
  }
  EXPECT_LT((D - fd).norm(), 1e-6 * D.norm());
  EXPECT_LT((D - D.transpose()).norm(), 1e-12 * D.norm()) << "a hyperelastic tangent is symmetric";
}

TEST_P(EachMaterial, DiscreteStressIsExactForSmallAndLargeSteps) {
  const Eigen::Matrix3d E_a = random_strain(rng, 0.2);
  for (double size : {0.3, 1e-3, 1e-7, 1e-12}) {
    const Eigen::Matrix3d E_b = E_a + random_strain(rng, size);
    const double dW = material.energy_density(E_b) - material.energy_density(E_a);
    const double work = contraction(material.discrete_stress(E_a, E_b), E_b - E_a);
    const double scale = std::abs(material.energy_density(E_a)) + material.stress(E_a).norm() * size;
    EXPECT_NEAR(work, dW, 1e-13 * scale) << "step " << size;
  }
}

TEST_P(EachMaterial, DiscreteStressTendsToTheStress) {
  const Eigen::Matrix3d E = random_strain(rng, 0.2);
  EXPECT_LT((material.discrete_stress(E, E) - material.stress(E)).norm(), 1e-13 * material.stress(E).norm());
  const Eigen::Matrix3d d = random_strain(rng, 1e-6);
  EXPECT_LT((material.discrete_stress(E - d, E + d) - material.stress(E)).norm(),
            1e-9 * material.stress(E).norm());
}

TEST_P(EachMaterial, DiscreteStressTangentMatchesFiniteDifferences) {
  for (double size : {0.2, 1e-3}) {
    const Eigen::Matrix3d E_a = random_strain(rng, 0.2), E_b = E_a + random_strain(rng, size);
    const Matrix6d D = material.discrete_stress_tangent(E_a, E_b);
    const double eps = 1e-7;
    Matrix6d fd;
    for (int k = 0; k < 6; ++k) {
      const Eigen::Matrix3d d = eps * voigt_direction(k);
      fd.col(k) =
          to_voigt_stress(material.discrete_stress(E_a, E_b + d) - material.discrete_stress(E_a, E_b - d)) /
          (2 * eps);
    }
    EXPECT_LT((D - fd).norm(), 1e-6 * D.norm()) << "step " << size;
  }
}

TEST_P(EachMaterial, SmallStrainTangentIsHookesLaw) {
  const SaintVenantKirchhoff hooke(2e3, material.name() == "neo_hookean" ? 0.45 : 0.3);
  const Eigen::Matrix3d zero = Eigen::Matrix3d::Zero();
  EXPECT_LT((material.tangent(zero) - hooke.tangent(zero)).norm(), 1e-12 * hooke.tangent(zero).norm());
  EXPECT_LT(material.stress(zero).norm(), 1e-12 * hooke.lambda());
}

TEST(NeoHookean, StressUnderUniaxialStrainMatchesTheClosedForm) {
  const NeoHookean m(2e3, 0.3);
  const Lame lame = Lame::from(2e3, 0.3);
  const double stretch = 0.4;  // strong compression, where SVK's stress has turned
  Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
  E(0, 0) = 0.5 * (stretch * stretch - 1);
  const double S11 =
      lame.mu * (1 - 1 / (stretch * stretch)) + lame.lambda * std::log(stretch) / (stretch * stretch);
  EXPECT_NEAR(m.stress(E)(0, 0), S11, 1e-12 * std::abs(S11));
  const double S22 = lame.lambda * std::log(stretch);  // C_22 = 1: only the volumetric part
  EXPECT_NEAR(m.stress(E)(1, 1), S22, 1e-12 * std::abs(S22));
  EXPECT_NEAR(m.stress(E)(0, 1), 0, 1e-12 * std::abs(S11));
}

TEST(NeoHookean, EnergyGrowsWithoutBoundAsTheVolumeVanishesAndIsUndefinedInverted) {
  const NeoHookean m(2e3, 0.3);
  double previous = 0;
  for (double stretch : {0.5, 0.1, 0.01, 1e-4}) {
    Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
    E(2, 2) = 0.5 * (stretch * stretch - 1);
    const double W = m.energy_density(E);
    EXPECT_GT(W, previous) << stretch;
    previous = W;
  }
  EXPECT_GT(previous, 1e4);
  Eigen::Matrix3d inverted = Eigen::Matrix3d::Zero();
  inverted(2, 2) = -0.6;  // C_33 = −0.2
  EXPECT_TRUE(std::isnan(m.energy_density(inverted)));
}

TEST(Cofactor, DerivativeMatchesFiniteDifferences) {
  std::mt19937 rng(3);
  const Eigen::Matrix3d C = Eigen::Matrix3d::Identity() + 2 * random_strain(rng, 0.2);
  const Eigen::Matrix3d A = random_strain(rng, 1);
  const double eps = 1e-6;
  const Eigen::Matrix3d fd = (cofactor(C + eps * A) - cofactor(C - eps * A)) / (2 * eps);
  EXPECT_LT((cofactor_derivative(C, A) - fd).norm(), 1e-8 * fd.norm());
  EXPECT_LT((cofactor(C) - C.determinant() * C.inverse()).norm(), 1e-13 * cofactor(C).norm());
}

TEST(MaterialRegistry, UnknownModelIsRefusedByName) {
  try {
    make_material({"mooney_rivlin", 1, 0.3, 1});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("\"mooney_rivlin\""), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stoss::fem
