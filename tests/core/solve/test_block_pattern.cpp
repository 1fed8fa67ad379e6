// BlockPattern (core/solve/block_pattern.hpp): every block's values land on their entries, whether its rows
// come in runs of three consecutive dofs (a node's: one slot kept per run and column) or not.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "core/solve/block_pattern.hpp"

namespace stoss::solve {
namespace {

/// Values that differ in every entry, so that a value on a wrong entry shows.
Eigen::MatrixXd distinct_values(int rows, int cols, double offset) {
  Eigen::MatrixXd values(rows, cols);
  for (int j = 0; j < cols; ++j)
    for (int i = 0; i < rows; ++i) values(i, j) = offset + i + 100.0 * j;
  return values;
}

TEST(BlockPattern, BlocksInNodeTriplesAndOthersScatterOntoTheirEntries) {
  const int n = 15;
  const std::vector<std::vector<int>> row_sets = {
      {0, 1, 2, 9, 10, 11},  // two nodes' dofs
      {3, 4, 5, 6, 7, 8},    // two neighbouring nodes: one run of six is two runs of three
      {4, 5, 6},             // three consecutive dofs that are not one node's
      {1, 2, 12, 13},        // not in threes
      {14},                  // one dof
      {0, 1, 2, 3, 4, 5, 12, 13, 14}};
  BlockPattern pattern;
  std::vector<int> ids;
  for (const auto& rows : row_sets) ids.push_back(pattern.add_block(rows, rows));
  ids.push_back(pattern.add_block({0, 1, 2}, {13, 14}));  // a rectangular block in triples
  pattern.build(n);
  pattern.zero();
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(n, n);
  for (size_t k = 0; k < row_sets.size(); ++k) {
    const auto& rows = row_sets[k];
    const Eigen::MatrixXd values = distinct_values(int(rows.size()), int(rows.size()), 1000.0 * k);
    pattern.scatter(ids[k], values);
    for (size_t j = 0; j < rows.size(); ++j)
      for (size_t i = 0; i < rows.size(); ++i) expected(rows[i], rows[j]) += values(i, j);
  }
  const Eigen::MatrixXd rectangular = distinct_values(3, 2, 7000.0);
  pattern.scatter(ids.back(), rectangular);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) expected(i, 13 + j) += rectangular(i, j);
  const Eigen::MatrixXd assembled = Eigen::MatrixXd(pattern.matrix());
  EXPECT_EQ(assembled, expected);
}

TEST(BlockPattern, ASparseMatrixOfTheMarkedRowsAloneAddsThoseRowsAndNoPatternElsewhere) {
  const int n = 6;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (std::abs(i - j) <= 2) dense(i, j) = 1.0 + i + 10.0 * j;
  const SparseMatrix S = dense.sparseView();
  const std::vector<char> rows = {1, 1, 1, 0, 0, 0};  // one node of two
  BlockPattern pattern;
  const int id = pattern.add_sparse(S, &rows);
  pattern.build(n);
  pattern.zero();
  pattern.scatter_sparse(id, S, 2.0);
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(n, n);
  expected.topRows(3) = 2.0 * dense.topRows(3);
  EXPECT_EQ(Eigen::MatrixXd(pattern.matrix()), expected);
  EXPECT_EQ(pattern.matrix().nonZeros(), 12 + 3) << "the marked rows' entries and the diagonal";
  EXPECT_THROW(pattern.build(n), std::logic_error) << "the entries are gone once built";
}

TEST(BlockPattern, SlotsOfBlocksNameTheSameEntriesInOrderWhateverElseThePatternHolds) {
  // Two patterns with the same two blocks after different others: the (column, row) order of slots_of is
  // the same in both, each entry once, though the slots themselves differ.
  const std::vector<int> a{3, 4, 5, 9}, b{4, 5, 6, 7, 8, 1};
  BlockPattern first, second;
  first.add_block({0, 1, 2});
  second.add_block({10, 11}, {2, 10});
  for (BlockPattern* P : {&first, &second}) {
    P->add_block(a);
    P->add_block(b);
    P->build(12);
    P->zero();
    P->scatter(1, distinct_values(4, 4, 0.5));
    P->scatter(2, distinct_values(6, 6, 0.25));
  }
  EXPECT_NE(first.generation(), second.generation()) << "no two patterns share a generation";
  const std::vector<int> slots_1 = first.slots_of(1, 3), slots_2 = second.slots_of(1, 3);
  ASSERT_EQ(slots_1.size(), 16u + 36u - 4u) << "entries (4|5, 4|5) are in both blocks, listed once";
  ASSERT_EQ(slots_2.size(), slots_1.size());
  EXPECT_NE(slots_1, slots_2) << "the other blocks moved the slots";
  for (size_t k = 0; k < slots_1.size(); ++k)
    ASSERT_EQ(first.matrix().valuePtr()[slots_1[k]], second.matrix().valuePtr()[slots_2[k]]) << "entry " << k;
}

}  // namespace
}  // namespace stoss::solve
