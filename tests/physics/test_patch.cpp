// The system shall reproduce a uniform SVK stress state on a distorted patch of elements and have a
// total mass equal to density × volume (docs/theory.md §1).
#include <gtest/gtest.h>

#include "core/fem/assembly.hpp"
#include "core/fem/saint_venant_kirchhoff.hpp"
#include "core/mesh/generators.hpp"

namespace stoss::fem {
namespace {

TEST(Patch, UniformStretchGivesZeroInteriorForceAndAnalyticTractions) {
  mesh::Mesh mesh;
  mesh::BodyMesh box = mesh::box({0, 0, 0}, {1, 1, 1}, {2, 2, 2});
  box.nodes[13] += Eigen::Vector3d(0.07, -0.05, 0.04);  // distort the interior node (1,1,1)
  mesh.add_body("patch", box);
  const auto material = std::make_shared<const SaintVenantKirchhoff>(2e3, 0.3);
  ElasticityTerm elasticity(mesh, precompute_mesh(mesh),
                            std::vector<std::shared_ptr<const Material>>(8, material));

  const Eigen::Matrix3d F = (Eigen::Matrix3d() << 1.08, 0.03, 0, 0.01, 0.95, 0.02, 0, 0.04, 1.03).finished();
  Eigen::VectorXd x(3 * mesh.node_count());
  for (int I = 0; I < mesh.node_count(); ++I) x.segment<3>(3 * I) = F * mesh.nodes[I];
  // h = 1 and x_n = x_1 = x: the midpoint rule's residual is exactly f_int(x).
  Eigen::VectorXd f = Eigen::VectorXd::Zero(x.size()), zero = Eigen::VectorXd::Zero(x.size());
  const time::StepContext at_x{x, zero, 1.0, time::ForceRule::midpoint()};
  elasticity.add(at_x, x, f, nullptr);

  EXPECT_LT(f.segment<3>(3 * 13).norm(), 1e-10) << "interior node of a homogeneous state carries no force";
  const Eigen::Matrix3d E = 0.5 * (F.transpose() * F - Eigen::Matrix3d::Identity());
  const Eigen::Matrix3d S = material->stress(E), P = F * S;  // first Piola–Kirchhoff
  Eigen::Vector3d top = Eigen::Vector3d::Zero();
  for (int I : mesh.surface_nodes("patch/top")) top += f.segment<3>(3 * I);
  EXPECT_LT((top - P * Eigen::Vector3d::UnitZ()).norm(), 1e-9 * P.norm()) << "top face resultant = P N A";
  const double W = 0.5 * material->lambda() * E.trace() * E.trace() + material->mu() * E.squaredNorm();
  EXPECT_NEAR(elasticity.energy(x), W, 1e-10 * W);
}

TEST(Patch, TotalMassIsDensityTimesVolume) {
  mesh::Mesh mesh;
  mesh.add_body("block", mesh::box({-1, 0, 2}, {2, 0.5, 3}, {3, 2, 4}));
  const auto geometry = precompute_mesh(mesh);
  const auto M = assemble_mass(mesh, geometry, std::vector<double>(mesh.element_count(), 7.5));
  EXPECT_NEAR(M.sum() / 3, 7.5 * 3 * 0.5 * 1, 1e-11);
}

}  // namespace
}  // namespace stoss::fem
