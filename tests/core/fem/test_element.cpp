// The hex8 kernels (every material; SVK's closed forms) against finite differences and analytic answers
// (docs/theory.md §1, §2.3, §6.1).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "core/fem/element.hpp"
#include "core/fem/neo_hookean.hpp"
#include "core/fem/saint_venant_kirchhoff.hpp"

namespace stoss::fem {
namespace {

Matrix83 unit_cube() {
  Matrix83 X;
  X << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  return X;
}

/// A distorted, rotated, stretched configuration: no symmetry left to hide an error.
struct Fixture {
  std::mt19937 rng{42};
  std::uniform_real_distribution<double> u{-1, 1};
  Matrix83 jitter(const Matrix83& X, double amount) {
    Matrix83 out = X;
    for (int i = 0; i < 8; ++i)
      for (int k = 0; k < 3; ++k) out(i, k) += amount * u(rng);
    return out;
  }
};

Vector24 flat(const Matrix83& x) {
  Vector24 v;
  for (int I = 0; I < 8; ++I) v.segment<3>(3 * I) = x.row(I).transpose();
  return v;
}
Matrix83 unflat(const Vector24& v) {
  Matrix83 x;
  for (int I = 0; I < 8; ++I) x.row(I) = v.segment<3>(3 * I).transpose();
  return x;
}

const SaintVenantKirchhoff material(1e4, 0.3);

/// The kernels' identities hold for every material behind fem::Material.
class Hex8EachMaterial : public ::testing::TestWithParam<std::shared_ptr<const Material>> {
 protected:
  const Material& material = *GetParam();
};
INSTANTIATE_TEST_SUITE_P(Materials, Hex8EachMaterial,
                         ::testing::Values(std::make_shared<const SaintVenantKirchhoff>(1e4, 0.3),
                                           std::make_shared<const NeoHookean>(1e4, 0.45)),
                         [](const auto& info) { return info.param->name(); });

TEST_P(Hex8EachMaterial, InternalForceIsTheGradientOfStrainEnergy) {
  Fixture fx;
  const ElementGeometry e = precompute_geometry(fx.jitter(unit_cube(), 0.1));
  const Matrix83 x = fx.jitter(unit_cube() * 1.1, 0.15);
  Vector24 f;
  internal_force(e, material, x, f, nullptr);
  Vector24 fd;
  const double eps = 1e-6;
  for (int j = 0; j < 24; ++j) {
    Vector24 p = flat(x), m = flat(x);
    p[j] += eps;
    m[j] -= eps;
    fd[j] = (strain_energy(e, material, unflat(p)) - strain_energy(e, material, unflat(m))) / (2 * eps);
  }
  EXPECT_LT((f - fd).norm() / fd.norm(), 1e-6);
}

TEST_P(Hex8EachMaterial, TangentMatchesFiniteDifferencesOfForce) {
  Fixture fx;
  const ElementGeometry e = precompute_geometry(fx.jitter(unit_cube(), 0.1));
  const Matrix83 x = fx.jitter(unit_cube() * 0.9, 0.15);
  Vector24 f;
  Matrix24 K;
  internal_force(e, material, x, f, &K);
  Matrix24 fd;
  const double eps = 1e-6;
  for (int j = 0; j < 24; ++j) {
    Vector24 p = flat(x), m = flat(x), fp, fm;
    p[j] += eps;
    m[j] -= eps;
    internal_force(e, material, unflat(p), fp, nullptr);
    internal_force(e, material, unflat(m), fm, nullptr);
    fd.col(j) = (fp - fm) / (2 * eps);
  }
  EXPECT_LT((K - fd).norm() / fd.norm(), 1e-6);
  EXPECT_LT((K - K.transpose()).norm() / K.norm(), 1e-12) << "the standard tangent is symmetric";
}

TEST_P(Hex8EachMaterial, DiscreteGradientIsExactOverAStep) {
  // (2.8): f̄ · (x_1 − x_n) = V(x_1) − V(x_n), to round-off.
  Fixture fx;
  const ElementGeometry e = precompute_geometry(fx.jitter(unit_cube(), 0.1));
  const Matrix83 x_n = fx.jitter(unit_cube() * 1.05, 0.1), x_1 = fx.jitter(unit_cube() * 0.95, 0.1);
  Vector24 f;
  discrete_gradient_force(e, material, x_n, x_1, f, nullptr);
  const double work = f.dot(flat(x_1) - flat(x_n));
  const double dV = strain_energy(e, material, x_1) - strain_energy(e, material, x_n);
  EXPECT_LT(std::abs(work - dV) / std::abs(dV), 1e-12);
}

TEST_P(Hex8EachMaterial, DiscreteGradientTangentMatchesFiniteDifferences) {
  Fixture fx;
  const ElementGeometry e = precompute_geometry(fx.jitter(unit_cube(), 0.1));
  const Matrix83 x_n = fx.jitter(unit_cube() * 1.05, 0.1), x_1 = fx.jitter(unit_cube() * 0.95, 0.1);
  Vector24 f;
  Matrix24 K;
  discrete_gradient_force(e, material, x_n, x_1, f, &K);
  Matrix24 fd;
  const double eps = 1e-6;
  for (int j = 0; j < 24; ++j) {
    Vector24 p = flat(x_1), m = flat(x_1), fp, fm;
    p[j] += eps;
    m[j] -= eps;
    discrete_gradient_force(e, material, x_n, unflat(p), fp, nullptr);
    discrete_gradient_force(e, material, x_n, unflat(m), fm, nullptr);
    fd.col(j) = (fp - fm) / (2 * eps);
  }
  EXPECT_LT((K - fd).norm() / fd.norm(), 1e-6);
}

TEST_P(Hex8EachMaterial, DiscreteGradientForceIsBalancedAndTorqueFree) {
  // §2.3: Σ_I f̄_I = 0 and Σ_I x_{m,I} × f̄_I = 0.
  Fixture fx;
  const ElementGeometry e = precompute_geometry(fx.jitter(unit_cube(), 0.1));
  const Matrix83 x_n = fx.jitter(unit_cube(), 0.2), x_1 = fx.jitter(unit_cube(), 0.2);
  Vector24 f;
  discrete_gradient_force(e, material, x_n, x_1, f, nullptr);
  const Matrix83 x_m = 0.5 * (x_n + x_1);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  for (int I = 0; I < 8; ++I) {
    sum += f.segment<3>(3 * I);
    torque += x_m.row(I).transpose().cross(Eigen::Vector3d(f.segment<3>(3 * I)));
  }
  EXPECT_LT(sum.norm() / f.norm(), 1e-13);
  EXPECT_LT(torque.norm() / f.norm(), 1e-13);
}

TEST(Hex8Element, UniformStretchReproducesSvkStressAnalytically) {
  // x = diag(s) X: F = diag(s), E = ½(s² − 1), S = λ tr E 1 + 2μE; nodal forces on the face x = 1
  // sum to S_11·F_11 × area (first Piola traction) and the energy is W(E) × volume.
  const Eigen::Vector3d s(1.1, 0.97, 1.02);
  const Matrix83 X = unit_cube();
  const Matrix83 x = X * s.asDiagonal();
  const ElementGeometry e = precompute_geometry(X);
  const Eigen::Matrix3d E =
      0.5 * (Eigen::Matrix3d(s.cwiseProduct(s).asDiagonal()) - Eigen::Matrix3d::Identity());
  const Eigen::Matrix3d S =
      material.lambda() * E.trace() * Eigen::Matrix3d::Identity() + 2 * material.mu() * E;
  Vector24 f;
  internal_force(e, material, x, f, nullptr);
  double face_force = 0;
  for (int I : {1, 2, 5, 6}) face_force += f[3 * I];
  EXPECT_NEAR(face_force, s[0] * S(0, 0), 1e-10 * std::abs(s[0] * S(0, 0)));
  const double W = 0.5 * material.lambda() * E.trace() * E.trace() + material.mu() * E.squaredNorm();
  EXPECT_NEAR(strain_energy(e, material, x), W, 1e-12 * W);
}

TEST(Hex8Element, ConsistentMassSumsToDensityTimesVolume) {
  Fixture fx;
  const Matrix83 X = unit_cube() * Eigen::Vector3d(2.0, 0.5, 3.0).asDiagonal();
  const ElementGeometry e = precompute_geometry(X);
  EXPECT_NEAR(consistent_mass(e, 7.0).sum(), 7.0 * 3.0, 1e-12);
  const Matrix8 M = consistent_mass(e, 1.0);
  EXPECT_LT((M - M.transpose()).norm(), 1e-15);
}

TEST(Hex8Element, InvertedElementIsRejectedWithItsGaussPoint) {
  Matrix83 X = unit_cube();
  X.row(6) = Eigen::RowVector3d(-0.5, -0.5, -0.5);
  try {
    precompute_geometry(X);
    FAIL() << "an inverted element was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("det J0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stoss::fem
