// The state hooks of PenaltyContactTerm (checkpoint and resume): per slave node what a converged step
// leaves for the next (§5.2 item 7), and the Coulomb work so far.
#include <string>

#include "core/contact/penalty/penalty_term.hpp"

namespace stoss::contact {

time::TermState PenaltyContactTerm::save_state() const {
  time::TermState s;
  auto& face = s.integers["face"];
  auto& xi = s.reals["xi"];
  auto& traction = s.reals["friction_traction"];
  auto& offset = s.reals["gap_offset"];
  for (const PenaltyNodeState& node : committed_) {
    face.push_back(node.face);
    xi.insert(xi.end(), node.xi.data(), node.xi.data() + 2);
    traction.insert(traction.end(), node.history.traction.data(), node.history.traction.data() + 3);
    offset.push_back(node.gap_offset);
  }
  s.reals["dissipated_energy"] = {dissipated_};
  s.integers["return_map_evaluations"] = {return_maps_};
  return s;
}

void PenaltyContactTerm::restore_state(const time::TermState& state, const Eigen::VectorXd&,
                                       const Eigen::VectorXd&) {
  const size_t n = surfaces_.slave_nodes.size();
  const auto& face = state.integer("face", n);
  const auto& xi = state.real("xi", 2 * n);
  const auto& traction = state.real("friction_traction", 3 * n);
  const auto& offset = state.real("gap_offset", n);
  std::vector<PenaltyNodeState> nodes(n);
  for (size_t i = 0; i < n; ++i) {
    if (face[i] < -1 || face[i] >= static_cast<std::int64_t>(surfaces_.faces.size()))
      throw std::invalid_argument("term state of " + name() + ": slave node " + std::to_string(i) +
                                  " names a face the pair does not have");
    nodes[i].face = static_cast<int>(face[i]);
    nodes[i].xi = Eigen::Vector2d(xi[2 * i], xi[2 * i + 1]);
    nodes[i].history.traction = Eigen::Vector3d(traction[3 * i], traction[3 * i + 1], traction[3 * i + 2]);
    nodes[i].gap_offset = offset[i];
  }
  committed_ = std::move(nodes);
  contacts_.clear();
  dissipated_ = state.real("dissipated_energy", 1)[0];
  return_maps_ = static_cast<long>(state.integer("return_map_evaluations", 1)[0]);
  ++generation_;
}

}  // namespace stoss::contact
