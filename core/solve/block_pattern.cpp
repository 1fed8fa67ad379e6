#include "core/solve/block_pattern.hpp"

#include <algorithm>
#include <atomic>
#include <stdexcept>

namespace stoss::solve {

int BlockPattern::add_block(std::vector<int> rows, std::vector<int> cols) {
  built_ = false;
  blocks_.push_back(Block{std::move(rows), std::move(cols), {}});
  return static_cast<int>(blocks_.size()) - 1;
}

int BlockPattern::add_sparse(const SparseMatrix& S, const std::vector<char>* rows) {
  built_ = false;
  std::vector<std::pair<int, int>> entries;
  std::vector<int> value_at;
  entries.reserve(rows ? 0 : S.nonZeros());
  for (int c = 0; c < S.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(S, c); it; ++it) {
      if (rows && !(*rows)[it.row()]) continue;
      entries.emplace_back(static_cast<int>(it.row()), c);
      if (rows) value_at.push_back(static_cast<int>(&it.value() - S.valuePtr()));
    }
  sparse_entries_.push_back(std::move(entries));
  sparse_value_at_.push_back(std::move(value_at));
  return static_cast<int>(sparse_entries_.size()) - 1;
}

void BlockPattern::scatter_sparse(int id, const SparseMatrix& S, double factor) {
  const std::vector<int>& slots = sparse_slots_[id];
  const std::vector<int>& value_at = sparse_value_at_[id];
  double* data = matrix_.valuePtr();
  const double* values = S.valuePtr();
  if (value_at.empty()) {
    for (size_t k = 0; k < slots.size(); ++k) data[slots[k]] += factor * values[k];
    return;
  }
  for (size_t k = 0; k < slots.size(); ++k) data[slots[k]] += factor * values[value_at[k]];
}

void BlockPattern::clear() {
  blocks_.clear();
  sparse_entries_.clear();
  sparse_value_at_.clear();
  sparse_slots_.clear();
  sparse_entries_released_ = false;
  built_ = false;
}

void BlockPattern::build(int n) {
  if (sparse_entries_released_ && !sparse_slots_.empty())
    throw std::logic_error("BlockPattern: built twice; clear() and register again");
  std::vector<std::vector<int>> columns(n);
  for (int i = 0; i < n; ++i) columns[i].push_back(i);
  for (const Block& b : blocks_)
    for (int c : b.cols)
      for (int r : b.rows) columns[c].push_back(r);
  for (const auto& entries : sparse_entries_)
    for (auto [r, c] : entries) columns[c].push_back(r);
  std::vector<int> outer(n + 1, 0), inner;
  for (int c = 0; c < n; ++c) {
    auto& col = columns[c];
    std::sort(col.begin(), col.end());
    col.erase(std::unique(col.begin(), col.end()), col.end());
    outer[c + 1] = outer[c] + static_cast<int>(col.size());
    inner.insert(inner.end(), col.begin(), col.end());
    std::vector<int>().swap(col);
  }
  matrix_ = SparseMatrix(n, n);
  matrix_.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), matrix_.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), matrix_.innerIndexPtr());
  matrix_.coeffs().setZero();
  for (Block& b : blocks_) {
    b.in_triples = rows_in_triples(b.rows);
    const size_t step = b.in_triples ? 3 : 1, kept = b.rows.size() / step;
    b.slots.resize(kept * b.cols.size());
    for (size_t j = 0; j < b.cols.size(); ++j)
      for (size_t i = 0; i < kept; ++i) b.slots[i + j * kept] = slot(b.rows[step * i], b.cols[j]);
  }
  sparse_slots_.assign(sparse_entries_.size(), {});
  for (size_t k = 0; k < sparse_entries_.size(); ++k) {
    sparse_slots_[k].reserve(sparse_entries_[k].size());
    for (auto [r, c] : sparse_entries_[k]) sparse_slots_[k].push_back(slot(r, c));
    std::vector<std::pair<int, int>>().swap(sparse_entries_[k]);  // the slots say it all now
  }
  sparse_entries_released_ = true;
  diagonal_slots_.resize(n);
  for (int i = 0; i < n; ++i) diagonal_slots_[i] = slot(i, i);
  built_ = true;
  static std::atomic<int> last_generation{0};
  generation_ = ++last_generation;
}

int BlockPattern::slot(int row, int col) const {
  const int* begin = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[col];
  const int* end = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(begin, end, row);
  if (it == end || *it != row) throw std::logic_error("BlockPattern: entry outside the pattern");
  return static_cast<int>(it - matrix_.innerIndexPtr());
}

std::vector<int> BlockPattern::slots_of(int first, int end) const {
  std::vector<std::pair<int, int>> entries;  // (column, row)
  for (int block = first; block < end; ++block)
    for (int c : blocks_[block].cols)
      for (int r : blocks_[block].rows) entries.emplace_back(c, r);
  std::sort(entries.begin(), entries.end());
  entries.erase(std::unique(entries.begin(), entries.end()), entries.end());
  std::vector<int> slots;
  slots.reserve(entries.size());
  for (auto [c, r] : entries) slots.push_back(slot(r, c));
  return slots;
}

void BlockPattern::zero() {
  matrix_.coeffs().setZero();
}

bool BlockPattern::rows_in_triples(const std::vector<int>& rows) {
  if (rows.empty() || rows.size() % 3 != 0) return false;
  for (size_t I = 0; I < rows.size(); I += 3)
    if (rows[I + 1] != rows[I] + 1 || rows[I + 2] != rows[I] + 2) return false;
  return true;
}

void BlockPattern::scatter(int block, const Eigen::Ref<const Eigen::MatrixXd>& values) {
  const Block& b = blocks_[block];
  double* data = matrix_.valuePtr();
  const Eigen::Index nr = static_cast<Eigen::Index>(b.rows.size());
  if (!b.in_triples) {
    for (Eigen::Index j = 0; j < values.cols(); ++j)
      for (Eigen::Index i = 0; i < nr; ++i) data[b.slots[i + j * nr]] += values(i, j);
    return;
  }
  const Eigen::Index runs = nr / 3;  // a run's three rows are neighbours in every column
  for (Eigen::Index j = 0; j < values.cols(); ++j)
    for (Eigen::Index I = 0; I < runs; ++I) {
      double* at = data + b.slots[I + j * runs];
      at[0] += values(3 * I, j);
      at[1] += values(3 * I + 1, j);
      at[2] += values(3 * I + 2, j);
    }
}

void BlockPattern::add_diagonal(int i, double value) {
  matrix_.valuePtr()[diagonal_slots_[i]] += value;
}

void BlockPattern::eliminate(const std::vector<char>& fixed) {
  for (int c = 0; c < matrix_.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(matrix_, c); it; ++it)
      if (fixed[c] || fixed[it.row()]) it.valueRef() = (it.row() == c) ? 1.0 : 0.0;
}

}  // namespace stoss::solve
