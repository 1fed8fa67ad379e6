// The elasticity term on several ranks (core/parallel/element_share.hpp, docs/many_machines.md): each rank
// adds the elements of its range, and after the sum over the ranks every rank holds the residual and the
// matrix of all elements, with the other terms' entries kept. Two ranks are played here in one process: each
// share's sum is the identity, and the two ranks' results are added by hand.
#include <gtest/gtest.h>

#include "core/fem/assembly.hpp"
#include "core/fem/neo_hookean.hpp"
#include "core/mesh/generators.hpp"
#include "core/parallel/element_share.hpp"

namespace stoss::fem {
namespace {

TEST(ElementShare, RangesCoverEveryElementOnceInOrder) {
  for (int size : {1, 2, 3, 5})
    for (int n : {0, 1, 4, 7, 100}) {
      int next = 0;
      for (int rank = 0; rank < size; ++rank) {
        const auto [first, last] = parallel::ElementShare{rank, size, nullptr}.range(n);
        EXPECT_EQ(first, next) << rank << " of " << size << ", n " << n;
        EXPECT_LE(last - first, n / size + 1);
        EXPECT_GE(last - first, n / size);
        next = last;
      }
      EXPECT_EQ(next, n);
    }
}

struct Assembled {
  Eigen::VectorXd R;
  Eigen::VectorXd values;  ///< the matrix's stored values
};

/// The term's add at a deformed x with share `share` set (unset after), starting from R = 0 and every matrix
/// entry `others` (what other terms would have put there).
Assembled assemble(const parallel::ElementShare& share, double others) {
  mesh::Mesh mesh;
  mesh.add_body("block", mesh::box({0, 0, 0}, {1, 0.5, 0.5}, {4, 2, 2}));
  const auto material = std::make_shared<const NeoHookean>(1e3, 0.3);
  ElasticityTerm term(mesh, precompute_mesh(mesh),
                      std::vector<std::shared_ptr<const Material>>(mesh.hex8.size(), material));
  solve::BlockPattern K;
  term.register_blocks(K);
  K.build(3 * mesh.node_count());
  K.zero();
  std::fill(K.matrix().valuePtr(), K.matrix().valuePtr() + K.matrix().nonZeros(), others);
  Eigen::VectorXd x = mesh.reference_positions(), v = Eigen::VectorXd::Zero(x.size());
  for (int I = 0; I < mesh.node_count(); ++I) x[3 * I + 2] += 0.1 * x[3 * I] * x[3 * I];  // bent
  const time::StepContext step{mesh.reference_positions(), v, 0.01, time::ForceRule::discrete_gradient()};
  Assembled out{Eigen::VectorXd::Zero(x.size()), {}};
  parallel::set_element_share(share);
  term.add(step, x, out.R, &K);
  parallel::set_element_share({});
  out.values = Eigen::Map<const Eigen::VectorXd>(K.matrix().valuePtr(), K.matrix().nonZeros());
  return out;
}

TEST(ElementShare, TwoRanksSharesSumToTheWholeTermAndKeepTheOtherEntries) {
  const auto identity = [](double*, long) {};  // each rank's sum over the ranks, played by hand below
  const Assembled whole = assemble({}, 0.0);
  const Assembled first = assemble({0, 2, identity}, 0.0), second = assemble({1, 2, identity}, 0.0);
  ASSERT_GT(whole.R.norm(), 0);
  EXPECT_GT((first.R - whole.R).norm(), 0.1 * whole.R.norm()) << "a rank alone has only its elements";
  EXPECT_LT((first.R + second.R - whole.R).norm(), 1e-13 * whole.R.norm());
  EXPECT_LT((first.values + second.values - whole.values).norm(), 1e-13 * whole.values.norm());

  const Assembled with_others = assemble({0, 2, identity}, 7.0);
  EXPECT_LT((with_others.values - first.values - Eigen::VectorXd::Constant(first.values.size(), 7.0)).norm(),
            1e-13 * whole.values.norm())
      << "the other terms' entries are added back once, not summed over the ranks";

  int sums = 0;
  const Assembled counted = assemble({1, 2, [&](double*, long count) { sums += count > 0; }}, 0.0);
  EXPECT_EQ(sums, 2) << "the forces and the matrix values are summed over the ranks";
  EXPECT_EQ(counted.R, second.R);
}

}  // namespace
}  // namespace stoss::fem
