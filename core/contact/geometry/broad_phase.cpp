#include "core/contact/geometry/broad_phase.hpp"

#include <algorithm>
#include <cmath>

namespace stoss::contact {
namespace {

Box point_box(const Eigen::Vector3d& p) {
  return Box(p, p);
}

Box inflated(Box b, double margin) {
  b.min().array() -= margin;
  b.max().array() += margin;
  return b;
}

double largest_motion(const PairSurfaces& s, const Eigen::VectorXd& x_n, const Eigen::VectorXd& x_pred) {
  double worst = 0;
  auto visit = [&](int I) {
    worst = std::max(worst, (x_pred.segment<3>(3 * I) - x_n.segment<3>(3 * I)).norm());
  };
  for (int I : s.slave_nodes) visit(I);
  for (const mesh::Quad& q : s.faces)
    for (int I : q) visit(I);
  return worst;
}

}  // namespace

BoxGrid::BoxGrid(std::vector<Box> boxes, double cell)
    : boxes_(std::move(boxes)), cell_(std::max(cell, 1e-300)) {
  for (const Box& b : boxes_) bounds_.extend(b);
  if (boxes_.empty()) return;
  const Eigen::Array3d extent = bounds_.sizes().array();
  const double max_cells = 8.0 * boxes_.size() + 64;
  dims_ = Eigen::Array3i::Ones();  // positions that are not finite (a diverging run): one cell for all
  while (extent.allFinite()) {     // counted in double: a huge extent must not overflow an int
    const Eigen::Array3d dims = (extent / cell_).ceil().max(1.0);
    if (dims.prod() <= max_cells) {
      dims_ = dims.cast<int>();
      break;
    }
    cell_ *= 2;
  }
  std::vector<int> count(dims_.prod() + 1, 0);
  auto for_cells = [&](const Box& b, auto visit) {
    const Eigen::Array3i lo = cell_of(b.min()), hi = cell_of(b.max());
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) visit(cell_index({i, j, k}));
  };
  for (const Box& b : boxes_) for_cells(b, [&](int c) { ++count[c + 1]; });
  start_.assign(count.size(), 0);
  for (size_t c = 1; c < count.size(); ++c) start_[c] = start_[c - 1] + count[c];
  items_.resize(start_.back());
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (int id = 0; id < static_cast<int>(boxes_.size()); ++id)
    for_cells(boxes_[id], [&](int c) { items_[fill[c]++] = id; });
}

Eigen::Array3i BoxGrid::cell_of(const Eigen::Vector3d& p) const {
  const Eigen::Array3d rel = ((p - bounds_.min()).array() / cell_).floor();
  Eigen::Array3i cell;
  for (int k = 0; k < 3; ++k)  // clamped before the cast: inf and NaN coordinates land in the grid too
    cell[k] = std::isnan(rel[k]) ? 0 : static_cast<int>(std::clamp(rel[k], 0.0, double(dims_[k] - 1)));
  return cell;
}

void BoxGrid::query(const Box& q, std::vector<int>& out) const {
  out.clear();
  if (boxes_.empty() || !bounds_.intersects(q)) return;
  const Eigen::Array3i lo = cell_of(q.min()), hi = cell_of(q.max());
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i) {
        const int c = cell_index({i, j, k});
        for (int at = start_[c]; at < start_[c + 1]; ++at)
          if (boxes_[items_[at]].intersects(q)) out.push_back(items_[at]);
      }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

Box BroadPhase::face_box(const PairSurfaces& s, int f, const Eigen::VectorXd& x) const {
  Box b;
  for (int I : s.faces[f]) b.extend(x.segment<3>(3 * I));
  return b;
}

Box BroadPhase::slave_box(const PairSurfaces& s, int i, const Eigen::VectorXd& x) const {
  return point_box(x.segment<3>(3 * s.slave_nodes[i]));
}

void BroadPhase::update(const PairSurfaces& s, const Eigen::VectorXd& x_n, const Eigen::VectorXd& x_pred) {
  margin_ = 2 * largest_motion(s, x_n, x_pred);
  face_boxes_.resize(s.faces.size());
  for (size_t f = 0; f < s.faces.size(); ++f) {
    const double pad = std::max(0.5 * s.face_size[f], margin_);  // §3.4
    face_boxes_[f] = inflated(face_box(s, f, x_n).extend(face_box(s, f, x_pred)), pad);
  }
  grid_ = BoxGrid(face_boxes_, s.mean_face_size);
  const double pad = std::max(0.5 * s.mean_face_size, margin_);
  slave_boxes_.resize(s.slave_nodes.size());
  candidates_.resize(s.slave_nodes.size());
  for (size_t i = 0; i < s.slave_nodes.size(); ++i) {
    slave_boxes_[i] = inflated(slave_box(s, i, x_n).extend(slave_box(s, i, x_pred)), pad);
    query_slave(static_cast<int>(i));
  }
  collect_near();
}

int BroadPhase::refresh(const PairSurfaces& s, const Eigen::VectorXd& x) {
  bool rebuild = false;
  for (size_t f = 0; f < s.faces.size(); ++f) {
    const Box now = face_box(s, f, x);
    if (face_boxes_[f].contains(now)) continue;
    face_boxes_[f].extend(inflated(now, std::max(0.5 * s.face_size[f], margin_)));
    rebuild = true;
  }
  if (rebuild) grid_ = BoxGrid(face_boxes_, s.mean_face_size);
  int redone = 0;
  const double pad = std::max(0.5 * s.mean_face_size, margin_);
  for (size_t i = 0; i < s.slave_nodes.size(); ++i) {
    const Box now = slave_box(s, i, x);
    const bool left = !slave_boxes_[i].contains(now);
    if (left) slave_boxes_[i].extend(inflated(now, pad));
    if (!left && !rebuild) continue;
    query_slave(static_cast<int>(i));
    ++redone;
  }
  if (redone) collect_near();
  return redone;
}

void BroadPhase::query_slave(int i) {
  grid_.query(slave_boxes_[i], candidates_[i]);
}

void BroadPhase::collect_near() {
  near_.clear();
  for (size_t i = 0; i < candidates_.size(); ++i)
    if (!candidates_[i].empty()) near_.push_back(static_cast<int>(i));
}

}  // namespace stoss::contact
