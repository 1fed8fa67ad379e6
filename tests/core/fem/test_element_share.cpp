// The elasticity term on several ranks (core/parallel/element_share.hpp, docs/many_machines.md): each rank
// adds every element with a node it owns, so that its own rows of the residual and the matrix are those of
// one process to the bit, and each position row of the residual comes from its owner. Two ranks are played
// here in one process: each share's sum is the identity, and the two ranks' residuals are added by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/fem/assembly.hpp"
#include "core/fem/neo_hookean.hpp"
#include "core/mesh/generators.hpp"
#include "core/parallel/element_share.hpp"

namespace stoss::fem {
namespace {

mesh::Mesh block_mesh() {
  mesh::Mesh mesh;
  mesh.add_body("block", mesh::box({0, 0, 0}, {1, 0.5, 0.5}, {4, 2, 2}));
  return mesh;
}

/// A partition of two parts with a ragged border: the nodes left of x = 0.4, and every other node left of
/// x = 0.6, on rank 0.
std::vector<int> ragged_parts(const mesh::Mesh& mesh) {
  const Eigen::VectorXd X = mesh.reference_positions();
  std::vector<int> part(mesh.node_count());
  for (int node = 0; node < mesh.node_count(); ++node)
    part[node] = X[3 * node] < 0.4 + 0.2 * (node % 2) ? 0 : 1;
  return part;
}

TEST(ElementShare, NodeGraphJoinsTheNodesOfEachElement) {
  mesh::Mesh mesh;
  mesh.add_body("two", mesh::box({0, 0, 0}, {2, 1, 1}, {2, 1, 1}));  // 12 nodes, 2 hex8 sharing a face
  std::vector<int> offsets, neighbours;
  parallel::node_graph(mesh.hex8, mesh.node_count(), offsets, neighbours);
  ASSERT_EQ(offsets.size(), 13u);
  int face_nodes = 0;
  for (int node = 0; node < 12; ++node) {
    const int degree = offsets[node + 1] - offsets[node];
    EXPECT_TRUE(degree == 7 || degree == 11) << "node " << node << ": " << degree;
    face_nodes += degree == 11;
    const std::set<int> distinct(neighbours.begin() + offsets[node], neighbours.begin() + offsets[node + 1]);
    EXPECT_EQ(int(distinct.size()), degree) << "no neighbour twice";
    EXPECT_EQ(distinct.count(node), 0u) << "no node its own neighbour";
  }
  EXPECT_EQ(face_nodes, 4);
}

TEST(ElementShare, EachRankHasTheElementsWithANodeOfItsOwn) {
  const mesh::Mesh mesh = block_mesh();
  const std::vector<int> part = ragged_parts(mesh);
  std::vector<int> taken(mesh.element_count(), 0);
  for (int rank : {0, 1}) {
    const parallel::ElementShare share = parallel::share_of(mesh.hex8, part, rank, 2, nullptr);
    EXPECT_TRUE(std::is_sorted(share.elements.begin(), share.elements.end()));
    std::set<int> listed(share.elements.begin(), share.elements.end());
    for (int e = 0; e < mesh.element_count(); ++e) {
      bool touches = false;
      for (int node : mesh.hex8[e]) touches |= part[node] == rank;
      EXPECT_EQ(listed.count(e) == 1, touches) << "element " << e << ", rank " << rank;
      taken[e] += touches;
    }
  }
  for (int e = 0; e < mesh.element_count(); ++e) EXPECT_GE(taken[e], 1) << "element " << e << " left out";
}

struct Assembled {
  Eigen::VectorXd R;
  solve::SparseMatrix K;
};

/// The term's add at a deformed x with share `share` set (unset after), starting from the same R and matrix
/// entries other terms would have put there. The term is built and its blocks registered before the share
/// is set, so that every call's matrix has one process's pattern and the three compare entry by entry.
Assembled assemble(const parallel::ElementShare& share) {
  const mesh::Mesh mesh = block_mesh();
  const auto material = std::make_shared<const NeoHookean>(1e3, 0.3);
  ElasticityTerm term(mesh, precompute_mesh(mesh),
                      std::vector<std::shared_ptr<const Material>>(mesh.hex8.size(), material));
  solve::BlockPattern K;
  term.register_blocks(K);
  K.build(3 * mesh.node_count());
  K.zero();
  double* values = K.matrix().valuePtr();
  for (Eigen::Index k = 0; k < K.matrix().nonZeros(); ++k) values[k] = 0.1 * double(k % 13);  // the others'
  Eigen::VectorXd x = mesh.reference_positions(), v = Eigen::VectorXd::Zero(x.size());
  for (int I = 0; I < mesh.node_count(); ++I) x[3 * I + 2] += 0.1 * x[3 * I] * x[3 * I];  // bent
  const time::StepContext step{mesh.reference_positions(), v, 0.01, time::ForceRule::discrete_gradient()};
  Assembled out{Eigen::VectorXd::LinSpaced(x.size(), -1.0, 1.0), {}};  // the other terms' residual
  parallel::set_element_share(share);
  term.add(step, x, out.R, &K);
  parallel::set_element_share({});
  out.K = K.matrix();
  return out;
}

TEST(ElementShare, TwoRanksGiveOneProcesssResidualAndTheirOwnRowsOfTheMatrixToTheBit) {
  const auto identity = [](double*, long) {};  // each rank's sum over the ranks, played by hand below
  const mesh::Mesh mesh = block_mesh();
  const std::vector<int> part = ragged_parts(mesh);
  const Assembled whole = assemble({});
  const Assembled first = assemble(parallel::share_of(mesh.hex8, part, 0, 2, identity));
  const Assembled second = assemble(parallel::share_of(mesh.hex8, part, 1, 2, identity));
  ASSERT_GT(whole.R.norm(), 0);
  const Eigen::VectorXd summed = first.R + second.R;
  for (Eigen::Index row = 0; row < whole.R.size(); ++row)
    ASSERT_EQ(summed[row], whole.R[row]) << "row " << row << ": the owner's value alone, the same bits";
  int own_entries = 0, partial_entries = 0;
  for (int col = 0; col < whole.K.outerSize(); ++col)
    for (solve::SparseMatrix::InnerIterator it(whole.K, col), a(first.K, col), b(second.K, col); it;
         ++it, ++a, ++b) {
      const int owner = part[it.row() / 3];
      const double own = owner == 0 ? a.value() : b.value(), other = owner == 0 ? b.value() : a.value();
      ASSERT_EQ(own, it.value()) << "entry (" << it.row() << ", " << col << ") of its owner's row";
      ++own_entries;
      partial_entries += other != it.value();
    }
  EXPECT_GT(partial_entries, own_entries / 10) << "the other rank's rows are partial and left so";

  int sums = 0;
  const Assembled counted = assemble(parallel::share_of(
      mesh.hex8, part, 1, 2, [&](double*, long count) { sums += count == 3L * mesh.node_count(); }));
  EXPECT_EQ(sums, 1) << "one sum per add: the position rows of the residual";
  EXPECT_EQ(counted.R, second.R);
}

/// The energy and the element stresses of a term built on rank `rank` of 2 (its Gauss data only), each
/// sum over the ranks played by hand: the identity.
struct Measured {
  double energy = 0;
  Eigen::VectorXd cauchy, von_mises;
};
Measured measure_on(const mesh::Mesh& mesh, const std::vector<int>& part, int rank,
                    const Eigen::VectorXd& x) {
  parallel::set_element_share(parallel::share_of(mesh.hex8, part, rank, 2, [](double*, long) {}));
  const auto material = std::make_shared<const NeoHookean>(1e3, 0.3);
  const ElasticityTerm term(mesh, precompute_mesh(mesh),
                            std::vector<std::shared_ptr<const Material>>(mesh.hex8.size(), material));
  Measured out;
  out.energy = term.energy(x);
  term.element_stresses(x, out.cauchy, out.von_mises);
  parallel::set_element_share({});
  return out;
}

TEST(ElementShare, TwoRanksWithTheirOwnGaussDataGiveTheEnergyAndEveryStressOfOneProcess) {
  const mesh::Mesh mesh = block_mesh();
  const std::vector<int> part = ragged_parts(mesh);
  Eigen::VectorXd x = mesh.reference_positions();
  for (int I = 0; I < mesh.node_count(); ++I) x[3 * I + 2] += 0.1 * x[3 * I] * x[3 * I];  // bent
  const auto material = std::make_shared<const NeoHookean>(1e3, 0.3);
  const ElasticityTerm whole(mesh, precompute_mesh(mesh),
                             std::vector<std::shared_ptr<const Material>>(mesh.hex8.size(), material));
  Eigen::VectorXd cauchy, von_mises;
  whole.element_stresses(x, cauchy, von_mises);
  const Measured first = measure_on(mesh, part, 0, x), second = measure_on(mesh, part, 1, x);
  ASSERT_GT(whole.energy(x), 0);
  EXPECT_GT(first.energy, 0.1 * whole.energy(x)) << "both ranks count elements";
  EXPECT_GT(second.energy, 0.1 * whole.energy(x));
  EXPECT_NEAR(first.energy + second.energy, whole.energy(x), 1e-14 * whole.energy(x))
      << "each element counted once";
  ASSERT_GT(von_mises.norm(), 0);
  EXPECT_EQ(first.cauchy + second.cauchy, cauchy) << "each element's stress from one rank, the same bits";
  EXPECT_EQ(first.von_mises + second.von_mises, von_mises);
}

}  // namespace
}  // namespace stoss::fem
