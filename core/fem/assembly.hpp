#pragma once
/// @file Whole-mesh pieces built from the element kernels: geometry, mass, and the elasticity and gravity
/// terms.

#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "core/fem/element.hpp"
#include "core/mesh/mesh.hpp"
#include "core/solve/block_pattern.hpp"
#include "core/time/term.hpp"

namespace stoss::fem {

/// Threads the element loops of ElasticityTerm::add use: the STOSS_THREADS environment variable when it
/// is a positive integer, else every core the machine has (one job alone uses both cores of the CI
/// machine; a service running several jobs at once sets STOSS_THREADS=1 for its workers). Results do
/// not depend on it: each thread computes whole elements and one thread sums them in element order.
int element_threads();
/// Overrides element_threads() for this process (0: back to STOSS_THREADS or the cores).
void set_element_threads(int threads);

/// Worker threads that live as long as their owner (a term, for the run): run() hands them contiguous
/// ranges of elements and waits, instead of starting threads at every residual (~50 µs each, ~650 times
/// in the seed's example). Not shared between owners, so two runs in one process never wait on each other.
class ElementThreads {
 public:
  ElementThreads() = default;
  ~ElementThreads();
  ElementThreads(const ElementThreads&) = delete;
  ElementThreads& operator=(const ElementThreads&) = delete;
  /// Runs body(e) for e in [begin, end) in `parts` contiguous ranges, the first on this thread, part t
  /// from begin + n t / parts on a worker (started on first need). Returns when every range is done.
  void run(int begin, int end, int parts, const std::function<void(int)>& body);

 private:
  void work(int part);
  std::vector<std::thread> workers_;  ///< worker k runs part k + 1
  std::mutex mutex_;
  std::condition_variable start_, done_;
  const std::function<void(int)>* body_ = nullptr;
  int begin_ = 0, end_ = 0, parts_ = 0, pending_ = 0;
  long round_ = 0;
  bool stop_ = false;
};

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
  /// h·f_alg and h·∂f_alg/∂x_1 of element e under the step's force rule.
  void element_step(const time::StepContext& step, int e, const Eigen::VectorXd& x_1, Vector24& f,
                    Matrix24* K) const;

  std::vector<mesh::Hex> hex8_;
  std::vector<ElementGeometry> geometry_;
  std::vector<std::shared_ptr<const Material>> material_;  ///< per element, shared per body
  std::vector<int> block_;
  std::vector<Vector24> force_n_;  ///< f_int(x_n) per element, cached for HHT
  /// One chunk of elements' forces and tangents, computed by the threads before they are summed.
  mutable std::vector<Vector24> chunk_force_;
  mutable std::vector<Matrix24> chunk_tangent_;
  mutable std::unique_ptr<ElementThreads> threads_ = std::make_unique<ElementThreads>();
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
