#pragma once
/// @file Two MPI ranks of a contact pair played in one process (core/contact/contact_term.hpp): each rank
/// computes the contact rows of the slave nodes it owns, and its sum over the ranks adds the other rank's
/// part, recorded in a first pass. Every rank shall then hold one process's rows and entries.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <vector>

#include "core/contact/contact_term.hpp"
#include "core/parallel/element_share.hpp"

namespace stoss::contact::test {

/// What a pair adds: its rows of R and its entries of K, less what the other terms had put there; and the
/// size of what they had put there, at which the sums round.
struct PairRows {
  Eigen::VectorXd R;
  Eigen::MatrixXd K;
  double others_R = 0, others_K = 0;
};

/// The pair's add at z with `share` set, on top of other terms' values (R: a ramp; K: 0.001 (row + 2 col)
/// at every entry). The pattern holds a block of `own_node`'s rows first, so that each rank's slots differ,
/// as they do when the elasticity registers its own elements only.
inline PairRows add_with(ContactTerm& term, const time::StepContext& step, const Eigen::VectorXd& z,
                         const parallel::ElementShare& share, int own_node) {
  parallel::set_element_share(share);
  solve::BlockPattern P;
  P.add_block({3 * own_node, 3 * own_node + 1, 3 * own_node + 2});
  term.register_blocks(P);
  P.build(static_cast<int>(z.size()));
  Eigen::MatrixXd others = Eigen::MatrixXd::Zero(z.size(), z.size());
  for (int col = 0; col < P.matrix().outerSize(); ++col)
    for (solve::SparseMatrix::InnerIterator it(P.matrix(), col); it; ++it)
      others(it.row(), col) = it.valueRef() = 0.001 * double(it.row() + 2 * col);
  const Eigen::VectorXd ramp = Eigen::VectorXd::LinSpaced(z.size(), -1.0, 1.0);
  Eigen::VectorXd R = ramp;
  term.add(step, z, R, &P);
  parallel::set_element_share({});
  return {R - ramp, Eigen::MatrixXd(P.matrix()) - others, ramp.norm(), others.norm()};
}

/// One process's rows, and each of two ranks' with the nodes left of x = −0.2 on rank 0.
struct TwoRanks {
  PairRows whole, first, second;
  std::vector<double> part[2];  ///< what each rank computed itself: the buffers of its sum
  int sums = 0;
};

inline TwoRanks play_two_ranks(ContactTerm& term, const mesh::Mesh& mesh, const time::StepContext& step,
                               const Eigen::VectorXd& z) {
  const Eigen::VectorXd X = mesh.reference_positions();
  std::vector<int> owner(mesh.node_count());
  for (int node = 0; node < mesh.node_count(); ++node) owner[node] = X[3 * node] < -0.2 ? 0 : 1;
  const int own_node[2] = {0, mesh.node_count() - 1};
  TwoRanks out;
  const auto share = [&](int rank, bool second_pass) {
    parallel::ElementShare s = parallel::share_of(mesh.hex8, owner, rank, 2, nullptr);
    s.sum = [&out, rank, second_pass](double* values, long count) {
      ++out.sums;
      if (!second_pass) return out.part[rank].assign(values, values + count);
      for (long i = 0; i < count; ++i) values[i] += out.part[1 - rank][i];
    };
    return s;
  };
  for (int rank : {0, 1}) add_with(term, step, z, share(rank, false), own_node[rank]);
  out.first = add_with(term, step, z, share(0, true), own_node[0]);
  out.second = add_with(term, step, z, share(1, true), own_node[1]);
  out.whole = add_with(term, step, z, {}, own_node[0]);
  return out;
}

/// Each rank computed a part, not all; one sum per add; both ranks hold one process's rows and entries, to
/// the round-off of adding them to the other terms' values.
inline void expect_one_process_rows(const TwoRanks& r) {
  EXPECT_EQ(r.sums, 4) << "one sum per add";
  ASSERT_EQ(r.part[0].size(), r.part[1].size());
  const Eigen::Map<const Eigen::VectorXd> part0(r.part[0].data(), r.part[0].size()),
      part1(r.part[1].data(), r.part[1].size());
  const Eigen::VectorXd both = part0 + part1;
  EXPECT_GT((both - part0).norm(), 0.1 * both.norm()) << "rank 0 computes some slave nodes, not all";
  EXPECT_GT((both - part1).norm(), 0.1 * both.norm()) << "rank 1 computes some slave nodes, not all";
  EXPECT_EQ(r.first.R, r.second.R) << "the same bits on every rank";
  ASSERT_GT(r.whole.R.norm(), 0);
  const double R_size = r.whole.R.norm() + r.whole.others_R, K_size = r.whole.K.norm() + r.whole.others_K;
  EXPECT_LE((r.first.R - r.whole.R).norm(), 1e-14 * R_size) << "one process's rows";
  ASSERT_GT(r.whole.K.norm(), 0);
  EXPECT_LE((r.first.K - r.whole.K).norm(), 1e-14 * K_size) << "one process's entries";
  EXPECT_LE((r.second.K - r.whole.K).norm(), 1e-14 * K_size);
}

}  // namespace stoss::contact::test
