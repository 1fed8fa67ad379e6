#pragma once
/// @file Broad phase of the contact search (docs/theory.md §3.4): master-face boxes in a uniform
/// grid, one candidate list per slave node and step, refreshed within the step only where a node
/// left the box it was searched with. Never an all-pairs loop: building the grid is O(faces), a
/// query visits the cells its box overlaps.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <span>
#include <vector>

#include "core/contact/geometry/surface.hpp"

namespace stoss::contact {

using Box = Eigen::AlignedBox3d;

/// Axis-aligned boxes sorted into a uniform grid (compressed: cell → box ids).
/// @note The cell size is the requested one, doubled until the grid has at most 8 cells per box
///       (plus 64), so memory stays O(boxes) however the boxes are spread.
class BoxGrid {
 public:
  BoxGrid() = default;
  BoxGrid(std::vector<Box> boxes, double cell);
  /// Replaces `out` by the ids of the boxes that overlap `query`, ascending and unique.
  void query(const Box& query, std::vector<int>& out) const;
  int size() const { return static_cast<int>(boxes_.size()); }

 private:
  Eigen::Array3i cell_of(const Eigen::Vector3d& p) const;  ///< clamped to the grid
  int cell_index(const Eigen::Array3i& c) const { return c[0] + dims_[0] * (c[1] + dims_[1] * c[2]); }

  std::vector<Box> boxes_;
  Box bounds_;
  double cell_ = 1;
  Eigen::Array3i dims_ = Eigen::Array3i::Ones();
  std::vector<int> start_, items_;  ///< ids of the boxes in cell c: items_[start_[c] .. start_[c+1])
};

/// Candidate master faces of every slave node of a pair for one step.
/// @note Boxes (§3.4): a master face's box holds its nodes at x_n and at the predictor x_n + h v_n,
///       inflated by max(½ face size, 2 max_I |x_pred,I − x_n,I|) (= 2 h max |v|, over the pair's
///       nodes); a slave node's box holds its two positions, inflated likewise with the mean face size.
class BroadPhase {
 public:
  /// Builds the boxes and the grid at x_n and x_pred, and every slave node's candidate list.
  void update(const PairSurfaces& s, const Eigen::VectorXd& x_n, const Eigen::VectorXd& x_pred);
  /// Within a step, at positions x: rebuilds the grid if a master node left its face's box and
  /// re-queries the slave nodes that left theirs (boxes grown to include x). Returns how many slave
  /// lists were redone (all of them after a rebuild).
  int refresh(const PairSurfaces& s, const Eigen::VectorXd& x);
  /// Candidate faces (ascending ids) of the i-th slave node of the pair.
  std::span<const int> candidates(int slave_index) const { return candidates_[slave_index]; }
  /// Indices (into slave_nodes) of the slave nodes with at least one candidate.
  const std::vector<int>& near_slaves() const { return near_; }

 private:
  Box slave_box(const PairSurfaces& s, int i, const Eigen::VectorXd& x) const;
  Box face_box(const PairSurfaces& s, int f, const Eigen::VectorXd& x) const;
  void query_slave(int i);
  void collect_near();

  double margin_ = 0;
  std::vector<Box> face_boxes_, slave_boxes_;
  BoxGrid grid_;
  std::vector<std::vector<int>> candidates_;
  std::vector<int> near_;
};

}  // namespace stoss::contact
