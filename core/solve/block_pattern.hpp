#pragma once
/// @file Sparse matrix whose pattern is the union of dense blocks, built once and refilled in place.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace stoss::solve {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

/// Collects dense blocks (element matrices), builds their union pattern once, and maps every block
/// entry to its slot in the value array, so refilling a matrix costs one pass over the entries.
class BlockPattern {
 public:
  /// Registers a block coupling rows × cols; returns its id for scatter(). Invalidates the pattern.
  int add_block(std::vector<int> rows, std::vector<int> cols);
  /// Registers the pattern of a sparse matrix of the same size, of the rows marked in `rows` alone when
  /// given (a rank's own, on several MPI ranks); returns its id for scatter_sparse().
  int add_sparse(const SparseMatrix& S, const std::vector<char>* rows = nullptr);
  /// Registers a square block rows × rows.
  int add_block(const std::vector<int>& dofs) { return add_block(dofs, dofs); }
  /// Builds the n×n pattern (diagonal always included) and the scatter maps, once per registration: it lets
  /// go of the sparse matrices' entries (register them again after clear() to build again).
  void build(int n);
  bool built() const { return built_; }
  /// The number of blocks registered so far: the id the next add_block returns.
  int block_count() const { return static_cast<int>(blocks_.size()); }
  /// Where the values of the entries of blocks [first, end) are in matrix().valuePtr(), each entry once, in
  /// the order of (column, row): the same order on every pattern that holds these blocks, whatever else it
  /// holds. Needs the built pattern.
  std::vector<int> slots_of(int first, int end) const;
  /// Forgets every block (call before registering a new set).
  void clear();

  /// Sets every stored value to zero, keeping the pattern.
  void zero();
  /// A(rows[i], cols[j]) += values(i, j) for the block's rows and cols.
  void scatter(int block, const Eigen::Ref<const Eigen::MatrixXd>& values);
  /// A += factor · S for a matrix registered with add_sparse (same pattern as then; the marked rows only).
  void scatter_sparse(int id, const SparseMatrix& S, double factor);
  /// A(i, i) += value.
  void add_diagonal(int i, double value);
  /// Replaces rows and columns of the marked dofs by identity rows (Dirichlet elimination).
  void eliminate(const std::vector<char>& fixed);

  const SparseMatrix& matrix() const { return matrix_; }
  SparseMatrix& matrix() { return matrix_; }
  /// Changes every time the pattern is rebuilt, to a number no pattern of the process had before: solvers
  /// redo their symbolic analysis on change, and what is kept for one pattern is never taken for another's.
  int generation() const { return generation_; }

 private:
  struct Block {
    std::vector<int> rows, cols;
    /// Value index of entry (i, j) at i + j * rows.size(); for rows in runs of three consecutive dofs (a
    /// node's), whose entries sit together in every column, only the first row of each run: (3I, j) at
    /// I + j * rows.size() / 3, a third of the indices (an 8-node element's block: 192 instead of 576).
    std::vector<int> slots;
    bool in_triples = false;
  };
  /// Whether a block's rows come in runs of three consecutive dofs.
  static bool rows_in_triples(const std::vector<int>& rows);
  int slot(int row, int col) const;

  std::vector<Block> blocks_;
  std::vector<std::vector<std::pair<int, int>>> sparse_entries_;  ///< (row, col) per registered sparse matrix
  /// Per registered sparse matrix: where each registered entry's value is in S (empty: all, in order).
  std::vector<std::vector<int>> sparse_value_at_;
  std::vector<std::vector<int>> sparse_slots_;
  bool sparse_entries_released_ = false;  ///< build let go of them
  std::vector<int> diagonal_slots_;
  SparseMatrix matrix_;
  bool built_ = false;
  int generation_ = 0;
};

}  // namespace stoss::solve
