#pragma once
// A block of St. Venant–Kirchhoff hexahedra for the load tests: mesh, mass and elasticity, and the energy
// and momentum the balance checks compare with the loads' work and impulse.

#include <memory>

#include "core/fem/assembly.hpp"
#include "core/fem/saint_venant_kirchhoff.hpp"
#include "core/mesh/generators.hpp"

namespace stoss::loads::test_utils {

struct Block {
  mesh::Mesh mesh;
  solve::SparseMatrix mass;
  std::unique_ptr<fem::ElasticityTerm> elasticity;
  double total_mass = 0, length = 0;

  Block(const Eigen::Vector3d& size, const std::array<int, 3>& divisions, double youngs_modulus,
        double poisson, double density) {
    mesh.add_body("block", mesh::box(Eigen::Vector3d::Zero(), size, divisions));
    const auto geometry = fem::precompute_mesh(mesh);
    mass = fem::assemble_mass(mesh, geometry, std::vector<double>(mesh.hex8.size(), density));
    auto material = std::make_shared<const fem::SaintVenantKirchhoff>(youngs_modulus, poisson);
    elasticity = std::make_unique<fem::ElasticityTerm>(
        mesh, geometry, std::vector<std::shared_ptr<const fem::Material>>(mesh.hex8.size(), material));
    total_mass = mass.sum() / 3;
    length = size.norm();
  }
  const std::vector<mesh::Quad>& surface(const std::string& name) const {
    return mesh.surface("block/" + name);
  }
  /// K + V (docs/theory.md (1.10)).
  double energy(const Eigen::VectorXd& x, const Eigen::VectorXd& v) const {
    return 0.5 * v.dot(mass * v) + elasticity->energy(x);
  }
  /// L = Σ_I p_I (1.11).
  Eigen::Vector3d momentum(const Eigen::VectorXd& v) const {
    const Eigen::VectorXd p = mass * v;
    return p.reshaped(3, p.size() / 3).rowwise().sum();
  }
};

}  // namespace stoss::loads::test_utils
