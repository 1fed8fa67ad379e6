#include "core/contact/contact_term.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>

#include "core/contact/geometry/assignment.hpp"
#include "core/contact/geometry/smooth_surface.hpp"
#include "core/parallel/element_share.hpp"

namespace stoss::contact {

ContactTerm::ContactTerm(const mesh::Mesh& mesh, const model::ContactPair& pair)
    : pair_(pair), surfaces_(pair_surfaces(mesh, pair.slave, pair.master)) {
  if (pair.master_surface == model::MasterSurface::smooth) {
    SmoothSurface smooth = smooth_surface(surfaces_.faces);
    if (!smooth.ok()) throw std::invalid_argument("contact master " + pair.master + ": " + smooth.problem);
    surfaces_.patches = std::move(smooth.patches);
  }
  std::set<int> nodes(surfaces_.slave_nodes.begin(), surfaces_.slave_nodes.end());
  for (int face = 0; face < static_cast<int>(surfaces_.faces.size()); ++face)
    for (int node : master_nodes(surfaces_, face)) nodes.insert(node);
  for (int node : nodes)
    for (int c = 0; c < 3; ++c) surface_rows_.push_back(3 * node + c);
}

void ContactTerm::register_blocks(solve::BlockPattern& pattern) {
  first_block_ = pattern.block_count();
  register_pair_blocks(pattern);
  end_block_ = pattern.block_count();
}

bool ContactTerm::computes(int slave) const {
  const parallel::ElementShare& share = parallel::element_share();
  return !share.shared() || share.owns(surfaces_.slave_nodes[slave]);
}

void ContactTerm::add(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                      solve::BlockPattern* K) const {
  if (parallel::element_share().shared()) return add_on_ranks(step, z, R, K);
  add_pair(step, z, R, K);
}

void ContactTerm::add_on_ranks(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                               solve::BlockPattern* K) const {
  if (K && slots_generation_ != K->generation()) {
    slots_ = K->slots_of(first_block_, end_block_);
    slots_generation_ = K->generation();
  }
  // The pair's values: its rows of R (positions of its nodes, then its auxiliaries) and its entries of K.
  std::vector<double*> cells;
  cells.reserve(surface_rows_.size() + auxiliary_count() + (K ? slots_.size() : 0));
  for (int row : surface_rows_) cells.push_back(&R[row]);
  for (int row = offset_; row < offset_ + auxiliary_count(); ++row) cells.push_back(&R[row]);
  if (K)
    for (int slot : slots_) cells.push_back(K->matrix().valuePtr() + slot);
  // They start from zero, so that after add_pair they hold this rank's part alone; the parts of the ranks
  // are summed, and what the other terms had put there is added back.
  std::vector<double> others(cells.size()), part(cells.size());
  for (size_t i = 0; i < cells.size(); ++i) std::swap(others[i], *cells[i]);
  add_pair(step, z, R, K);
  for (size_t i = 0; i < cells.size(); ++i) part[i] = *cells[i];
  parallel::element_share().sum(part.data(), static_cast<long>(part.size()));  // the same bits on every rank
  for (size_t i = 0; i < cells.size(); ++i) *cells[i] = others[i] + part[i];
}

void ContactTerm::contact_pressure(Eigen::VectorXd& p) const {
  for (const auto& [node, value] : pressure_) p[node] = value;
}

void ContactTerm::log(const time::StepContext& step, const std::string& line) const {
  if (step.log && *step.log) (*step.log)(name() + ": " + line);
}

namespace {

/// Edges of the master surface that belong to one face only: the surface's boundary.
std::set<std::pair<int, int>> boundary_edges(const std::vector<mesh::Quad>& faces) {
  std::map<std::pair<int, int>, int> count;
  for (const mesh::Quad& q : faces)
    for (int k = 0; k < 4; ++k) ++count[std::minmax(q[k], q[(k + 1) % 4])];
  std::set<std::pair<int, int>> out;
  for (const auto& [edge, n] : count)
    if (n == 1) out.insert(edge);
  return out;
}

/// Whether the projection ξ onto face q leaves it across an edge in `boundary` (theory.md §3.4): the node
/// lies beyond the master's footprint. Face edges by corner ξ (segment.cpp): ξ₂ < −1 across (0, 1),
/// ξ₁ > 1 across (1, 2), ξ₂ > 1 across (2, 3), ξ₁ < −1 across (3, 0).
bool leaves_across(const Eigen::Vector2d& xi, const mesh::Quad& q,
                   const std::set<std::pair<int, int>>& boundary) {
  const bool past[4] = {xi[1]<-1, xi[0]> 1, xi[1] > 1, xi[0] < -1};
  for (int k = 0; k < 4; ++k)
    if (past[k] && boundary.count(std::minmax(q[k], q[(k + 1) % 4]))) return true;
  return false;
}

/// Of the slave nodes no face accepts: those level with some candidate face (§3.4), and among them those
/// beyond the master's footprint (a projection leaves the surface across its boundary). The rest are the
/// NTS blind spot between faces.
struct Unaccepted {
  int level = 0, outside_footprint = 0;
};

Unaccepted classify(const PairSurfaces& surfaces, const BroadPhase& broad, const std::vector<int>& unaccepted,
                    const Eigen::VectorXd& x) {
  Unaccepted out;
  if (unaccepted.empty()) return out;
  const std::set<std::pair<int, int>> boundary = boundary_edges(surfaces.faces);
  for (int i : unaccepted) {
    const Eigen::Vector3d x_s = x.segment<3>(3 * surfaces.slave_nodes[i]);
    bool level = false, outside = false;
    for (int f : broad.candidates(i)) {
      const Projection p = project_on(x_s, f, surfaces, x).projection;
      if (!p.converged || std::abs(p.gap) >= NarrowPhase::max_depth_ratio * surfaces.face_size[f]) continue;
      level = true;
      outside = outside || leaves_across(p.xi, surfaces.faces[f], boundary);
    }
    out.level += level;
    out.outside_footprint += level && outside;
  }
  return out;
}

}  // namespace

void ContactTerm::measure_closest_penetration(const time::StepContext& step, const Eigen::VectorXd& x) {
  std::vector<int> unaccepted;
  for (int i : broad_.near_slaves()) {
    const Eigen::Vector3d x_s = x.segment<3>(3 * surfaces_.slave_nodes[i]);
    const FaceProjection best = best_face(x_s, broad_.candidates(i), surfaces_, x);
    if (best.found())
      report_.max_penetration = std::max(report_.max_penetration, -best.projection.gap);
    else
      unaccepted.push_back(i);
  }
  const Unaccepted u = classify(surfaces_, broad_, unaccepted, x);
  report_.unassigned += u.level;
  report_.outside_footprint += u.outside_footprint;
  if (surfaces_.smooth()) measure_faceted_penetration(x);
  // Only a node between two faces is helped by a finer master mesh; beyond the master's boundary there
  // is no face to give it, and the hint would be wrong.
  const bool nts =
      pair_.discretization == model::Discretization::node_to_segment;  // mortar has no blind spot
  if (const int blind = report_.unassigned - report_.outside_footprint; nts && blind > 0)
    log(step,
        std::to_string(blind) +
            " slave node(s) level with the master surface project onto no face between two of its faces "
            "(NTS blind spot, §3.4): no contact element for them; refine the master mesh");
}

void ContactTerm::measure_faceted_penetration(const Eigen::VectorXd& x) {
  for (int i : broad_.near_slaves()) {
    const Eigen::Vector3d x_s = x.segment<3>(3 * surfaces_.slave_nodes[i]);
    double closest = std::numeric_limits<double>::infinity(), gap = 0;
    for (int f : broad_.candidates(i)) {
      const Projection p = closest_point_projection(x_s, face_positions(surfaces_.faces[f], x));
      if (!accepts(p, NarrowPhase::eps_ext, NarrowPhase::max_depth_ratio * surfaces_.face_size[f])) continue;
      if (std::abs(p.gap) < closest) closest = std::abs(p.gap), gap = p.gap;
    }
    report_.max_faceted_penetration = std::max(report_.max_faceted_penetration, -gap);
  }
}

std::string ContactTerm::scientific(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3e", v);
  return buffer;
}

}  // namespace stoss::contact
