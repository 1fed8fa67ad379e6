#include "core/contact/mortar/mortar_term.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <optional>
#include <utility>

#include "core/contact/mortar/frame_indifferent_gradient.hpp"

namespace stoss::contact {
namespace {

/// Activation threshold on the nodal gap g̃_j / D_jj, as §3.5: 1e-10 × the mean face size.
constexpr double activation_gap = 1e-10;
/// A slave node activates only once the master covers at least this fraction of its support: D_jj ≥ ½ Σ ∫ N_j
/// over its slave faces that overlap a master face (its faces that face away, a box's sides, do not count).
/// On a partly covered support the dual basis (4.77), negative over part of each face, makes D_jj small or
/// negative and g̃_j / D_jj meaningless (the two-balls example's first contact: D_jj = 5.5e-5 where a covered
/// node has 0.065, g̃_j / D_jj = −24).
constexpr double covered_fraction = 0.5;
/// closes_touching (static steps): a nodal gap g̃_j / D_jj up to this fraction of the mean face size touches,
/// as the NTS term's.
constexpr double touching_gap = 1e-8;

/// The discrete-gradient rule evaluates the gaps where the midpoint form does, x_m and x_{n+1}, and corrects
/// the midpoint gradient along the step's deformation (4.87).
time::ForceRule configuration_rule(const time::ForceRule& rule) {
  return rule.kind == time::ForceRule::Kind::discrete_gradient ? time::ForceRule::midpoint() : rule;
}

/// A face pair's 24 coordinates, slave nodes then master nodes (PairGaps' order).
mortar::Vector24 pair_coordinates(const SegmentNodes& slave, const SegmentNodes& master) {
  mortar::Vector24 x;
  for (int K = 0; K < 4; ++K)
    x.segment<3>(3 * K) = slave.row(K).transpose(), x.segment<3>(12 + 3 * K) = master.row(K).transpose();
  return x;
}

/// Corner box of a face at positions x and x + dx.
Eigen::AlignedBox3d face_box(const mesh::Quad& q, const Eigen::VectorXd& x, const Eigen::VectorXd& y) {
  Eigen::AlignedBox3d box;
  for (int node : q)
    box.extend(Eigen::Vector3d(x.segment<3>(3 * node))), box.extend(Eigen::Vector3d(y.segment<3>(3 * node)));
  return box;
}

double box_size(const Eigen::AlignedBox3d& b) {
  return b.diagonal().norm();
}

}  // namespace

MortarContactTerm::MortarContactTerm(const mesh::Mesh& mesh, const model::ContactPair& pair,
                                     const time::ForceRule& rule)
    : ContactTerm(mesh, pair),
      rule_(configuration_rule(rule)),
      exact_energy_(rule.kind == time::ForceRule::Kind::discrete_gradient),
      slave_faces_(mesh.surface(pair.slave)) {
  if (surfaces_.smooth())
    throw std::invalid_argument("contact pair " + pair.slave + " / " + pair.master +
                                ": mortar integrates on the faceted master surface only");
  const size_t n = surfaces_.slave_nodes.size();
  active_.assign(n, 0);
  start_active_ = committed_active_ = active_;
  toggles_.assign(n, 0);
  lambda_ = lambda_n_ = frozen_ = committed_frozen_ = target_ = committed_target_ = Eigen::VectorXd::Zero(n);
  length_ = surfaces_.mean_face_size;
}

int MortarContactTerm::slave_index(int node) const {
  const auto it = std::lower_bound(surfaces_.slave_nodes.begin(), surfaces_.slave_nodes.end(), node);
  return static_cast<int>(it - surfaces_.slave_nodes.begin());
}

void MortarContactTerm::find_face_pairs(const time::StepContext& step) {
  const Eigen::VectorXd predicted = step.x_n + step.h * step.v_n;
  std::vector<Eigen::AlignedBox3d> master_boxes;
  for (const mesh::Quad& q : surfaces_.faces) master_boxes.push_back(face_box(q, step.x_n, predicted));
  std::vector<FacePair> pairs;
  for (size_t s = 0; s < slave_faces_.size(); ++s) {
    const Eigen::AlignedBox3d box = face_box(slave_faces_[s], step.x_n, predicted);
    for (size_t m = 0; m < master_boxes.size(); ++m) {
      const double margin = 0.25 * (box_size(box) + box_size(master_boxes[m]));
      Eigen::AlignedBox3d grown = box;
      grown.min().array() -= margin;
      grown.max().array() += margin;
      if (!grown.intersects(master_boxes[m])) continue;
      FacePair p;
      p.slave_face = static_cast<int>(s);
      p.master_face = static_cast<int>(m);
      for (int K = 0; K < 4; ++K) p.slave_index[K] = slave_index(slave_faces_[s][K]);
      pairs.push_back(p);
    }
  }
  // A pair found again keeps its dofs and block (the pattern is rebuilt only on a new generation); a new one
  // has none until a slave node of it is active (refresh_structure). Both lists are ordered by (slave,
  // master).
  const auto before = [](const FacePair& a, const FacePair& b) {
    return std::pair(a.slave_face, a.master_face) < std::pair(b.slave_face, b.master_face);
  };
  auto old = pairs_.begin();
  for (FacePair& p : pairs) {
    while (old != pairs_.end() && before(*old, p)) ++old;
    if (old != pairs_.end() && !before(p, *old)) {
      p.dofs = old->dofs, p.block = old->block;
    } else {
      set_dofs(p);
    }
  }
  pairs_ = std::move(pairs);
}

void MortarContactTerm::set_dofs(FacePair& p) const {
  p.dofs.clear();
  for (const mesh::Quad* q : {&slave_faces_[p.slave_face], &surfaces_.faces[p.master_face]})
    for (int node : *q)
      for (int i = 0; i < 3; ++i) p.dofs.push_back(3 * node + i);
  for (int j : p.slave_index) p.dofs.push_back(offset_ + j);
}

bool MortarContactTerm::has_active_node(const FacePair& p) const {
  return std::any_of(p.slave_index.begin(), p.slave_index.end(), [&](int j) { return active_[j] != 0; });
}

void MortarContactTerm::refresh_structure() {
  if (std::any_of(pairs_.begin(), pairs_.end(),
                  [&](const FacePair& p) { return has_active_node(p) != (p.block >= 0); }))
    ++generation_;
}

void MortarContactTerm::register_pair_blocks(solve::BlockPattern& pattern) {
  for (FacePair& p : pairs_) {
    set_dofs(p);
    p.block =
        has_active_node(p) ? pattern.add_block(p.dofs) : -1;  // only these have a tangent (pair_contribution)
  }
  diagonal_blocks_.clear();
  for (int j = 0; j < auxiliary_count(); ++j) diagonal_blocks_.push_back(pattern.add_block({offset_ + j}));
}

Eigen::Vector4d MortarContactTerm::frozen_gaps(const FacePair& p) const {
  Eigen::Vector4d c;
  for (int k = 0; k < 4; ++k) c[k] = frozen_[p.slave_index[k]];
  return c;
}

Eigen::Vector4d MortarContactTerm::gaps_at_start(const FacePair& p) const {
  return p.gap_n - frozen_gaps(p).cwiseProduct(p.basis_integral_n);  // ∫ Φ_j (g − ḡ⁰_j) at x_n (4.83)
}

mortar::PairGaps MortarContactTerm::gaps(const FacePair& p, const Eigen::VectorXd& x) const {
  return mortar::pair_gaps(face_positions(slave_faces_[p.slave_face], x),
                           face_positions(surfaces_.faces[p.master_face], x), mortar::Multipliers::dual,
                           frozen_gaps(p));
}

void MortarContactTerm::nodal_gaps(const Eigen::VectorXd& x, Eigen::VectorXd& gap, Eigen::VectorXd& weight,
                                   Eigen::VectorXd* support, std::vector<mortar::PairGaps>* pairs) const {
  gap = weight = Eigen::VectorXd::Zero(auxiliary_count());
  if (pairs) pairs->clear();
  std::vector<double> facing(slave_faces_.size(), 0);  // per slave face: the largest ψ of its overlaps
  for (const FacePair& p : pairs_) {
    const mortar::PairGaps g = gap_values(p, x);
    if (pairs) pairs->push_back(g);
    if (g.area > 0) facing[p.slave_face] = std::max(facing[p.slave_face], g.facing_weight);
    for (int K = 0; K < 4; ++K) gap[p.slave_index[K]] += g.gap[K], weight[p.slave_index[K]] += g.weight[K];
  }
  if (!support) return;
  *support = Eigen::VectorXd::Zero(auxiliary_count());
  for (size_t s = 0; s < slave_faces_.size(); ++s) {
    if (facing[s] == 0) continue;
    const SegmentNodes y = face_positions(slave_faces_[s], x);
    const double quarter_area = facing[s] * (y.row(2) - y.row(0)).cross(y.row(3) - y.row(1)).norm() / 8;
    for (int node : slave_faces_[s]) (*support)[slave_index(node)] += quarter_area;
  }
}

bool MortarContactTerm::covered(double weight, double support) {
  return weight > covered_fraction * support;
}

void MortarContactTerm::prepare_step(const time::StepContext& step) {
  active_ = committed_active_;
  lambda_ = lambda_n_;
  frozen_ = committed_frozen_;
  target_ = committed_target_;
  std::fill(toggles_.begin(), toggles_.end(), 0);
  broad_.update(surfaces_, step.x_n, step.x_n + step.h * step.v_n);
  report_ = ContactReport{};
  find_face_pairs(step);
  for (FacePair& p : pairs_) p.force_n = previous_force(p, step.x_n);
  std::vector<mortar::PairGaps> at_start;
  nodal_gaps(step.x_n, gap_n_, weight_n_, &support_n_, &at_start);
  basis_integral_n_ = Eigen::VectorXd::Zero(auxiliary_count());
  for (size_t k = 0; k < pairs_.size(); ++k) {
    FacePair& p = pairs_[k];
    p.basis_integral_n = at_start[k].basis_integral;
    p.gap_n = at_start[k].gap + frozen_gaps(p).cwiseProduct(p.basis_integral_n);  // with no frozen gap
    for (int K = 0; K < 4; ++K) basis_integral_n_[p.slave_index[K]] += p.basis_integral_n[K];
  }
  release_uncovered();
  if (pair_.closes_touching) activate_touching();
  start_active_ = active_;
  refresh_structure();
}

void MortarContactTerm::release_uncovered() {
  for (int j = 0; j < auxiliary_count(); ++j)
    if (active_[j] && !(weight_n_[j] > 0)) release(j);
}

void MortarContactTerm::release(int j) {
  active_[j] = 0, lambda_[j] = 0, frozen_[j] = target_[j] = 0, ++report_.releases;
}

void MortarContactTerm::activate_touching() {
  for (int j = 0; j < auxiliary_count(); ++j)
    if (!active_[j] && covered(weight_n_[j], support_n_[j]) &&
        gap_n_[j] <= touching_gap * length_ * weight_n_[j])
      active_[j] =
          1;  // closes its gap (an inactive node freezes none); released after the pass if in tension
}

void MortarContactTerm::begin_step(const time::StepContext& step, Eigen::VectorXd& z) {
  initialize_auxiliaries(step, z);
}

void MortarContactTerm::initialize_auxiliaries(const time::StepContext&, Eigen::VectorXd& z) {
  for (int j = 0; j < auxiliary_count(); ++j) z[offset_ + j] = active_[j] ? lambda_[j] : 0.0;
}

std::optional<Eigen::Matrix<double, 1, 24>> MortarContactTerm::previous_force(
    const FacePair& p, const Eigen::VectorXd& x_n) const {
  Eigen::Vector4d lambda_n;
  for (int k = 0; k < 4; ++k) lambda_n[k] = lambda_n_[p.slave_index[k]];
  if (rule_.previous_weight == 0 || lambda_n.isZero(0)) return std::nullopt;
  return Eigen::Matrix<double, 1, 24>(lambda_n.transpose() * gaps(p, x_n).gradient);  // (4.82)
}

mortar::PairGaps MortarContactTerm::gap_values(const FacePair& p, const Eigen::VectorXd& x) const {
  const mortar::FacePairIntegrals<double> r = mortar::face_pair_integrals<double>(
      mortar::quad_nodes(face_positions(slave_faces_[p.slave_face], x)),
      mortar::quad_nodes(face_positions(surfaces_.faces[p.master_face], x)), mortar::Multipliers::dual,
      mortar::Integrals::gaps, frozen_gaps(p));
  mortar::PairGaps g;
  g.gap = r.gap, g.weight = r.weight, g.area = r.area, g.basis_integral = r.basis_integral;
  g.facing_weight = r.facing_weight;
  return g;
}

void MortarContactTerm::pair_contribution(const FacePair& p, const time::StepContext& step,
                                          const Eigen::VectorXd& z, const Eigen::VectorXd& x_1,
                                          const Eigen::VectorXd& x_theta, bool tangent,
                                          PairContribution& out) const {
  out.rows.setZero();
  out.tangent = false;
  const double w = step.force_factor * rule_.weight;
  Eigen::Vector4d lambda;
  for (int k = 0; k < 4; ++k) lambda[k] = z[offset_ + p.slave_index[k]];
  // What this call needs: Σ λ_j ∂²g̃_j/∂x² for a tangent with λ ≠ 0, ∂g̃/∂x for any tangent or λ ≠ 0, else
  // the gaps' values.
  const bool loaded = !lambda.isZero(0), curved = tangent && loaded, sloped = tangent || loaded;
  // Faces that overlap neither at x_n, x_θ nor x_{n+1} add nothing: a value costs µs, a derivative ms.
  if (sloped && p.gap_n.isZero(0) && gap_values(p, x_theta).area == 0 &&
      (rule_.theta == 1 || gap_values(p, x_1).area == 0))
    return;
  mortar::Matrix24 H = mortar::Matrix24::Zero();
  const SegmentNodes s = face_positions(slave_faces_[p.slave_face], x_theta);
  const SegmentNodes m = face_positions(surfaces_.faces[p.master_face], x_theta);
  const Eigen::Vector4d frozen = frozen_gaps(p);
  const mortar::PairGaps g = curved   ? mortar::pair_gaps(s, m, mortar::Multipliers::dual, lambda, H, frozen)
                             : sloped ? mortar::pair_gaps(s, m, mortar::Multipliers::dual, frozen)
                                      : gap_values(p, x_theta);
  const mortar::PairGaps g_1 = rule_.theta == 1 ? g : tangent ? gaps(p, x_1) : gap_values(p, x_1);
  // The force's gradients and ∂(Σ λ_j ∂g̃_j)/∂x_{n+1}: the discrete gradient (4.87), (4.88) or ∂g̃/∂x(x_θ).
  mortar::PairDiscreteGradient force{g.gradient, rule_.theta * H};
  if (exact_energy_ && sloped) {
    const mesh::Quad &slave = slave_faces_[p.slave_face], &master = surfaces_.faces[p.master_face];
    const mortar::Vector24 y_n =
        pair_coordinates(face_positions(slave, step.x_n), face_positions(master, step.x_n));
    const mortar::Vector24 y_1 = pair_coordinates(face_positions(slave, x_1), face_positions(master, x_1));
    force = mortar::discrete_gradient({y_n, y_1, gaps_at_start(p), g_1, g, curved ? &H : nullptr, length_},
                                      lambda);
  }
  if (loaded) out.rows.head<24>() = w * (lambda.transpose() * force.gradient).transpose();  // (4.82), (4.87)
  for (int k = 0; k < 4; ++k)
    if (active_[p.slave_index[k]]) out.rows[24 + k] = g_1.gap[k];  // (4.83)
  if (!tangent) return;
  out.tangent = true;
  out.block.setZero();
  out.block.topLeftCorner<24, 24>() = w * force.tangent;               // (4.81), (4.82), (4.88)
  out.block.topRightCorner<24, 4>() = w * force.gradient.transpose();  // (4.82), (4.87)
  for (int k = 0; k < 4; ++k)
    if (active_[p.slave_index[k]]) out.block.block<1, 24>(24 + k, 0) = g_1.gradient.row(k);  // (4.83)
}

void MortarContactTerm::add_pair(const time::StepContext& step, const Eigen::VectorXd& z, Eigen::VectorXd& R,
                                 solve::BlockPattern* K) const {
  const Eigen::VectorXd x_1 = z.head(step.x_n.size());
  const Eigen::VectorXd x_theta = rule_.evaluation_point(step.x_n, x_1);
  // A pair with no active node adds nothing but its λ_n part: its force is λ = 0, it has no gap rows, and its
  // multipliers' columns of K meet rows λ_j = 0 that fix their increments to zero, so they change no Newton
  // step. Nor has it a block in the pattern, whose factorisation then costs what the contact really couples.
  // On several ranks a face pair is the rows of the rank that owns its slave face's first node (computes).
  const auto computed = [&](const FacePair& p) { return computes(p.slave_index[0]); };
  std::vector<int> loaded;  // the pairs with an active node, computed on the worker threads
  for (size_t k = 0; k < pairs_.size(); ++k)
    if (has_active_node(pairs_[k]) && computed(pairs_[k])) loaded.push_back(static_cast<int>(k));
  contributions_.resize(loaded.size());
  threads_->for_each(0, static_cast<int>(loaded.size()), parallel::worker_threads(), 1, [&](int i) {
    PairContribution& out = contributions_[i];
    try {
      pair_contribution(pairs_[loaded[i]], step, z, x_1, x_theta, K != nullptr, out);
      out.failed = false;
    } catch (const std::exception&) {
      out.failed = true;  // a face's projection folds (4.75) or a slave face's is not convex (4.70)
    }
  });
  // Summed on this thread in pair order: the same bits for every thread count.
  const double w_n = step.force_factor * rule_.previous_weight;
  for (size_t k = 0, i = 0; k < pairs_.size(); ++k) {
    const FacePair& p = pairs_[k];
    if (w_n != 0 && p.force_n && computed(p))
      for (int a = 0; a < 24; ++a) R[p.dofs[a]] += w_n * (*p.force_n)[a];  // h w_n λ_n ∂g̃/∂x(x_n) (4.82)
    if (i == loaded.size() || loaded[i] != static_cast<int>(k)) continue;
    const PairContribution& c = contributions_[i++];
    if (c.failed) {
      // No configuration to integrate on: a residual that is not finite makes Newton backtrack, or the step
      // shorter.
      R[p.dofs[0]] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    for (int a = 0; a < 28; ++a) R[p.dofs[a]] += c.rows[a];
    if (K && c.tangent) K->scatter(p.block, c.block);
  }
  for (int j = 0; j < auxiliary_count(); ++j) {
    if (!computes(j)) continue;
    if (active_[j]) {
      R[offset_ + j] -= target_[j];  // (4.83)
      continue;
    }
    R[offset_ + j] += z[offset_ + j];  // λ_j = 0 (4.83)
    if (K) K->scatter(diagonal_blocks_[j], Eigen::Matrix<double, 1, 1>::Ones());
  }
}

bool MortarContactTerm::update_active_set(const time::StepContext& step, const Eigen::VectorXd& z) {
  Eigen::VectorXd gap, weight, support;
  nodal_gaps(z.head(step.x_n.size()), gap, weight, &support);
  bool changed = false;
  for (int j = 0; j < auxiliary_count(); ++j) {
    lambda_[j] = z[offset_ + j];
    if (active_[j] && lambda_[j] > 0) {
      if (toggles_[j] >= (step.inertia ? 1 : 2)) {  // anti-cycling (§3.5); static: may take back its own once
        log(step, "slave node " + std::to_string(surfaces_.slave_nodes[j]) +
                      " kept active with tensile λ = " + scientific(lambda_[j]) +
                      " (it already changed state in this step)");
        continue;
      }
      release(j), ++toggles_[j], changed = true;
    } else if (!active_[j] && covered(weight[j], support[j]) &&
               gap[j] < -activation_gap * length_ * weight[j] && toggles_[j] == 0) {
      const bool freezes = impact() == model::ImpactMode::persist || impact() == model::ImpactMode::located;
      // ḡ⁰_j (§4.5, (4.83)); a node its master does not cover at x_n has no nodal gap there: it keeps its
      // weighted gap instead, g̃⁰_j = g̃_j(x_n), so that its constraint too is zero at x_n
      const bool nodal = freezes && covered(basis_integral_n_[j], support_n_[j]);
      frozen_[j] = nodal ? gap_n_[j] / basis_integral_n_[j] : 0.0;
      target_[j] = freezes && !nodal ? gap_n_[j] : 0.0;
      active_[j] = 1, lambda_[j] = 0, ++toggles_[j], ++report_.activations, changed = true;
    }
  }
  if (changed) refresh_structure();
  return changed;
}

void MortarContactTerm::end_step(const time::StepContext& step, const Eigen::VectorXd& z) {
  const Eigen::VectorXd x = z.head(step.x_n.size());
  Eigen::VectorXd gap, weight;
  nodal_gaps(x, gap, weight);
  pressure_.clear();
  report_.energy_jump = 0;
  report_.active = 0;
  report_.contact_area = 0;
  for (int j = 0; j < auxiliary_count(); ++j) {
    lambda_[j] = active_[j] ? z[offset_ + j] : 0.0;
    if (!active_[j]) continue;
    ++report_.active;
    if (!start_active_[j]) {
      const double gap_at_start =
          gap_n_[j] - frozen_[j] * basis_integral_n_[j] - target_[j];  // (4.83) at x_n
      report_.energy_jump += lambda_[j] * gap_at_start;                // analogue of (4.11)
      report_.max_new_gap_target = std::max(report_.max_new_gap_target, frozen_[j] + target_[j] / weight[j]);
    }
    report_.max_own_face_penetration =
        std::max(report_.max_own_face_penetration, -(gap[j] - target_[j]) / weight[j]);
    // (4.84): λ_j is conjugate to g̃_j, so slave node j's force is λ_j D_jj n and its pressure −λ_j.
    if (weight[j] > 0) pressure_.emplace_back(surfaces_.slave_nodes[j], std::max(-lambda_[j], 0.0));
    if (lambda_[j] < 0)
      report_.contact_area += weight[j];  // Σ D_jj of the active nodes in compression (4.84)
  }
  lambda_n_ = lambda_;
  committed_active_ = active_;
  committed_frozen_ = frozen_;
  committed_target_ = target_;
  measure_closest_penetration(step, x);
}

double MortarContactTerm::auxiliary_residual_measure(const Eigen::VectorXd& R,
                                                     const time::MeasureScales&) const {
  double worst = 0;
  for (int j = 0; j < auxiliary_count(); ++j)
    if (active_[j])
      worst = std::max(worst, std::abs(R[offset_ + j]) / (surfaces_.tributary_area[j] * length_));
  return worst;
}

time::TermState MortarContactTerm::save_state() const {
  time::TermState s;
  s.integers["active"].assign(committed_active_.begin(), committed_active_.end());
  s.reals["lambda"].assign(lambda_n_.data(), lambda_n_.data() + lambda_n_.size());
  s.reals["frozen_gap"].assign(committed_frozen_.data(), committed_frozen_.data() + committed_frozen_.size());
  s.reals["target"].assign(committed_target_.data(), committed_target_.data() + committed_target_.size());
  return s;
}

void MortarContactTerm::restore_state(const time::TermState& state, const Eigen::VectorXd&,
                                      const Eigen::VectorXd&) {
  const size_t n = surfaces_.slave_nodes.size();
  const std::vector<std::int64_t>& active = state.integer("active", n);
  const std::vector<double>& lambda = state.real("lambda", n);
  const std::vector<double>& frozen = state.real("frozen_gap", n);
  const std::vector<double>& target = state.real("target", n);
  committed_active_.assign(active.begin(), active.end());
  lambda_n_ = lambda_ = Eigen::Map<const Eigen::VectorXd>(lambda.data(), static_cast<Eigen::Index>(n));
  committed_frozen_ = Eigen::Map<const Eigen::VectorXd>(frozen.data(), static_cast<Eigen::Index>(n));
  committed_target_ = Eigen::Map<const Eigen::VectorXd>(target.data(), static_cast<Eigen::Index>(n));
  pairs_.clear();  // the next prepare_step finds them at x_n and lays them out anew
  ++generation_;
}

}  // namespace stoss::contact
