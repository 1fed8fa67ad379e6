#pragma once
/// @file Whole-mesh pieces built from the element kernels: geometry, mass, and the elasticity and gravity
/// terms.

#include <functional>
#include <memory>
#include <vector>

#include "core/fem/element.hpp"
#include "core/mesh/mesh.hpp"
#include "core/parallel/worker_threads.hpp"
#include "core/solve/block_pattern.hpp"
#include "core/time/term.hpp"

namespace stoss::fem {

/// Gauss data of every element; throws std::invalid_argument naming the element if one is inverted.
std::vector<ElementGeometry> precompute_mesh(const mesh::Mesh& mesh);

/// The element's nodes as rows of an 8×3 matrix, from stacked positions x.
Matrix83 gather(const mesh::Hex& hex, const Eigen::VectorXd& x);

/// Global dof indices 3I + i of an element, in element order.
std::vector<int> element_dofs(const mesh::Hex& hex);

/// Consistent mass matrix M ⊗ 1 (3 per node) (1.9); density per element.
solve::SparseMatrix assemble_mass(const mesh::Mesh& mesh, const std::vector<ElementGeometry>& geometry,
                                  const std::vector<double>& element_density);

/// Strain energy of hyperelastic bodies (a Material per element): f_int with the force rule of the scheme.
/// On several ranks (parallel::element_share, set before it is built) it keeps the Gauss data of the rank's
/// elements only; energy and element_stresses then sum over the ranks, so every rank calls them at once.
class ElasticityTerm : public time::Term {
 public:
  ElasticityTerm(const mesh::Mesh& mesh, std::vector<ElementGeometry> geometry,
                 std::vector<std::shared_ptr<const Material>> element_material);
  std::string name() const override { return "elasticity"; }
  double energy(const Eigen::VectorXd& x) const override;
  void register_blocks(solve::BlockPattern& pattern) override;
  void begin_step(const time::StepContext& step, Eigen::VectorXd& z) override;
  void add(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
           solve::BlockPattern* K) const override;
  /// The element stresses of a frame at positions x: Cauchy stress (average_cauchy_stress), 6 per element in
  /// XDMF Tensor6 order (xx, xy, xz, yy, yz, zz), and von Mises, 1 per element.
  void element_stresses(const Eigen::VectorXd& x, Eigen::VectorXd& cauchy, Eigen::VectorXd& von_mises) const;

 private:
  /// add's forces and tangents of `count` elements, into R and K: elements[0 … count) (every element in
  /// order when `elements` is null).
  void add_elements(const time::StepContext& step, const Eigen::VectorXd& z, const int* elements, int count,
                    Eigen::VectorXd& R, solve::BlockPattern* K) const;
  /// add on several ranks (parallel::element_share): the elements with a node of this rank's, then each
  /// position row of R from the rank that owns it.
  void add_shared(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                  solve::BlockPattern* K) const;
  /// f(e) for each element this process computes: every one, or on several ranks the rank's
  /// (parallel::ElementShare::elements).
  void for_each_own(const std::function<void(int)>& f) const;
  /// f(e) for each element this process counts in a total over the ranks: every one, or on several ranks
  /// those whose first node it owns, so that each element counts on one rank.
  void for_each_counted(const std::function<void(int)>& f) const;
  /// The Gauss data of element e (on several ranks, one of this rank's elements).
  const ElementGeometry& geometry(int e) const;
  /// h·f_alg and h·∂f_alg/∂x_1 of element e under the step's force rule.
  void element_step(const time::StepContext& step, int e, const Eigen::VectorXd& x_1, Vector24& f,
                    Matrix24* K) const;

  std::vector<mesh::Hex> hex8_;
  std::vector<ElementGeometry> geometry_;  ///< per element; on several ranks per element of this rank's
  std::vector<int> geometry_at_;           ///< several ranks: each element's place in geometry_, or -1
  std::vector<std::shared_ptr<const Material>> material_;  ///< per element, shared per body
  std::vector<int> block_;
  std::vector<Vector24> force_n_;  ///< f_int(x_n) per element, cached for HHT
  /// One chunk of elements' forces and tangents, computed by the threads before they are summed.
  mutable std::vector<Vector24> chunk_force_;
  mutable std::vector<Matrix24> chunk_tangent_;
  mutable std::unique_ptr<parallel::WorkerThreads> threads_ = std::make_unique<parallel::WorkerThreads>();
};

/// Dead load of gravity: V = −Σ (M g)·x, exact in every scheme.
class GravityTerm : public time::Term {
 public:
  GravityTerm(const solve::SparseMatrix& mass, const Eigen::Vector3d& g);
  std::string name() const override { return "gravity"; }
  double energy(const Eigen::VectorXd& x) const override { return -load_.dot(x); }
  void register_blocks(solve::BlockPattern&) override {}
  void add(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
           solve::BlockPattern* K) const override;
  /// f_ext = M g stacked (3 per node).
  const Eigen::VectorXd& load() const { return load_; }

 private:
  Eigen::VectorXd load_;  ///< f_ext = M g stacked
};

}  // namespace stoss::fem
