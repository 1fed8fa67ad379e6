#include "core/fem/assembly.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "core/parallel/element_share.hpp"

namespace stoss::fem {
namespace {

/// Elements per chunk of ElasticityTerm::add: its forces and tangents are held until summed (a chunk of
/// 512 tangents is 2.4 MB); residual-only chunks are larger.
constexpr int tangent_chunk = 512, force_chunk = 4096;

}  // namespace

std::vector<ElementGeometry> precompute_mesh(const mesh::Mesh& mesh) {
  std::vector<ElementGeometry> out;
  out.reserve(mesh.hex8.size());
  const Eigen::VectorXd X = mesh.reference_positions();
  for (size_t e = 0; e < mesh.hex8.size(); ++e) {
    try {
      out.push_back(precompute_geometry(gather(mesh.hex8[e], X)));
    } catch (const std::invalid_argument& err) {
      throw std::invalid_argument("element " + std::to_string(e) + ": " + err.what());
    }
  }
  return out;
}

Matrix83 gather(const mesh::Hex& hex, const Eigen::VectorXd& x) {
  Matrix83 out;
  for (int I = 0; I < 8; ++I) out.row(I) = x.segment<3>(3 * hex[I]).transpose();
  return out;
}

std::vector<int> element_dofs(const mesh::Hex& hex) {
  std::vector<int> dofs(24);
  for (int I = 0; I < 8; ++I)
    for (int k = 0; k < 3; ++k) dofs[3 * I + k] = 3 * hex[I] + k;
  return dofs;
}

solve::SparseMatrix assemble_mass(const mesh::Mesh& mesh, const std::vector<ElementGeometry>& geometry,
                                  const std::vector<double>& element_density) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(mesh.hex8.size() * 64 * 3);
  for (size_t e = 0; e < mesh.hex8.size(); ++e) {
    const Matrix8 M = consistent_mass(geometry[e], element_density[e]);
    for (int I = 0; I < 8; ++I)
      for (int J = 0; J < 8; ++J)
        for (int k = 0; k < 3; ++k)
          entries.emplace_back(3 * mesh.hex8[e][I] + k, 3 * mesh.hex8[e][J] + k, M(I, J));
  }
  const int n = 3 * mesh.node_count();
  solve::SparseMatrix M(n, n);
  M.setFromTriplets(entries.begin(), entries.end());
  return M;
}

ElasticityTerm::ElasticityTerm(const mesh::Mesh& mesh, std::vector<ElementGeometry> geometry,
                               std::vector<std::shared_ptr<const Material>> element_material)
    : hex8_(mesh.hex8), geometry_(std::move(geometry)), material_(std::move(element_material)) {
  const parallel::ElementShare& share = parallel::element_share();
  if (!share.shared()) return;
  // Several ranks: the Gauss data of this rank's elements alone (core/parallel/element_share.hpp).
  std::vector<ElementGeometry> own;
  own.reserve(share.elements.size());
  geometry_at_.assign(hex8_.size(), -1);
  for (int e : share.elements) {
    geometry_at_[e] = static_cast<int>(own.size());
    own.push_back(geometry_[e]);
  }
  geometry_ = std::move(own);
}

const ElementGeometry& ElasticityTerm::geometry(int e) const {
  return geometry_[geometry_at_.empty() ? e : geometry_at_[e]];
}

void ElasticityTerm::for_each_own(const std::function<void(int)>& f) const {
  const parallel::ElementShare& share = parallel::element_share();
  if (share.shared())
    for (int e : share.elements) f(e);
  else
    for (int e = 0; e < static_cast<int>(hex8_.size()); ++e) f(e);
}

void ElasticityTerm::for_each_counted(const std::function<void(int)>& f) const {
  const parallel::ElementShare& share = parallel::element_share();
  for_each_own([&](int e) {  // on several ranks, each element by the owner of its first node
    if (!share.shared() || share.owns(hex8_[e][0])) f(e);
  });
}

double ElasticityTerm::energy(const Eigen::VectorXd& x) const {
  double V = 0;
  for_each_counted([&](int e) { V += strain_energy(geometry(e), *material_[e], gather(hex8_[e], x)); });
  return parallel::total_over_ranks(V);
}

void ElasticityTerm::element_stresses(const Eigen::VectorXd& x, Eigen::VectorXd& cauchy,
                                      Eigen::VectorXd& von_mises_stress) const {
  const Eigen::Index E = static_cast<Eigen::Index>(hex8_.size());
  cauchy = Eigen::VectorXd::Zero(6 * E);
  von_mises_stress = Eigen::VectorXd::Zero(E);
  for_each_counted([&](int e) {
    const Eigen::Matrix3d sigma = average_cauchy_stress(geometry(e), *material_[e], gather(hex8_[e], x));
    cauchy.segment<6>(6 * e) << sigma(0, 0), sigma(0, 1), sigma(0, 2), sigma(1, 1), sigma(1, 2), sigma(2, 2);
    von_mises_stress[e] = von_mises(sigma);
  });
  const parallel::ElementShare& share = parallel::element_share();
  if (!share.shared()) return;
  share.sum(cauchy.data(), cauchy.size());  // the other ranks' elements are zeros here
  share.sum(von_mises_stress.data(), von_mises_stress.size());
}

void ElasticityTerm::register_blocks(solve::BlockPattern& pattern) {
  block_.assign(hex8_.size(), -1);  // add scatters the own elements only: about a kB of slots each
  for_each_own([&](int e) { block_[e] = pattern.add_block(element_dofs(hex8_[e])); });
}

void ElasticityTerm::begin_step(const time::StepContext& step, Eigen::VectorXd&) {
  if (step.rule.previous_weight == 0) return;
  force_n_.resize(hex8_.size());
  for_each_own([&](int e) {  // add asks for these only
    internal_force(geometry(e), *material_[e], gather(hex8_[e], step.x_n), force_n_[e], nullptr);
  });
}

void ElasticityTerm::element_step(const time::StepContext& step, int e, const Eigen::VectorXd& x_1,
                                  Vector24& f, Matrix24* K) const {
  const Matrix83 xe_1 = gather(hex8_[e], x_1);
  const time::ForceRule& rule = step.rule;
  if (rule.kind == time::ForceRule::Kind::discrete_gradient) {
    discrete_gradient_force(geometry(e), *material_[e], gather(hex8_[e], step.x_n), xe_1, f, K);  // (2.6)
    return;
  }
  internal_force(geometry(e), *material_[e], rule.evaluation_point(gather(hex8_[e], step.x_n), xe_1), f, K);
  if (rule.weight != 1) f *= rule.weight;
  if (rule.previous_weight != 0) f += rule.previous_weight * force_n_[e];  // (2.5), (2.11), (2.12)
  if (K && rule.weight * rule.theta != 1) *K *= rule.weight * rule.theta;
}

void ElasticityTerm::add(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                         solve::BlockPattern* K) const {
  if (parallel::element_share().shared()) return add_shared(step, z, R, K);
  add_elements(step, z, nullptr, static_cast<int>(hex8_.size()), R, K);
}

void ElasticityTerm::add_elements(const time::StepContext& step, const Eigen::VectorXd& z,
                                  const int* elements, int count, Eigen::VectorXd& R,
                                  solve::BlockPattern* K) const {
  // Threads compute whole elements into the chunk's buffers; this thread sums them in element order, so
  // R and K are the same bits for every thread count.
  const auto element = [elements](int i) { return elements ? elements[i] : i; };
  const int chunk = K ? tangent_chunk : force_chunk, threads = parallel::worker_threads();
  chunk_force_.resize(std::min(count, chunk));
  if (K) chunk_tangent_.resize(std::min(count, chunk));
  for (int first = 0; first < count; first += chunk) {
    const int last = std::min(count, first + chunk);
    const std::function<void(int)> body = [&](int i) {
      element_step(step, element(i), z, chunk_force_[i - first], K ? &chunk_tangent_[i - first] : nullptr);
    };
    threads_->for_each(first, last, threads, 16, body);  // no thread for fewer than 16 elements
    for (int i = first; i < last; ++i) {
      const int e = element(i);
      const Vector24& f = chunk_force_[i - first];
      for (int I = 0; I < 8; ++I) R.segment<3>(3 * hex8_[e][I]) += step.force_factor * f.segment<3>(3 * I);
      if (K) K->scatter(block_[e], step.force_factor * chunk_tangent_[i - first]);
    }
  }
}

void ElasticityTerm::add_shared(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                                solve::BlockPattern* K) const {
  // Every element with a node of this rank's, in element order: its own rows of R and K are the sums one
  // process makes (core/parallel/element_share.hpp); the other rows of K stay partial, never read.
  const parallel::ElementShare& share = parallel::element_share();
  add_elements(step, z, share.elements.data(), static_cast<int>(share.elements.size()), R, K);
  // Each position row of R from its owner alone: x + 0 + … + 0 is x to the bit on every rank.
  const int nodes = static_cast<int>(share.node_part.size());
  for (int node = 0; node < nodes; ++node)
    if (!share.owns(node)) R.segment<3>(3 * node).setZero();
  share.sum(R.data(), 3L * nodes);
}

GravityTerm::GravityTerm(const solve::SparseMatrix& mass, const Eigen::Vector3d& g) {
  const Eigen::VectorXd g_stacked = g.replicate(mass.rows() / 3, 1);
  load_ = mass * g_stacked;
}

void GravityTerm::add(const time::StepContext& step, const Eigen::VectorXd&, Eigen::VectorXd& R,
                      solve::BlockPattern*) const {
  R.head(load_.size()) -= step.force_factor * load_;  // a linear potential is exact in every scheme (§2.3)
}

}  // namespace stoss::fem
