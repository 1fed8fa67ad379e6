#include "core/contact/contact_mass.hpp"

#include <algorithm>
#include <stdexcept>

namespace stoss::contact {
namespace {

bool midpoint_type(model::Scheme s) {
  return s == model::Scheme::energy_momentum || s == model::Scheme::midpoint;
}

/// The nodes sharing an element with each node.
std::vector<std::vector<int>> element_neighbours(const mesh::Mesh& mesh) {
  std::vector<std::vector<int>> out(mesh.node_count());
  for (const auto& hex : mesh.hex8)
    for (int a : hex)
      for (int b : hex)
        if (a != b) out[a].push_back(b);
  for (auto& n : out) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  return out;
}

/// Row s of P (§4.6.1): equal weights on the nearest neighbours off the massless set.
std::vector<int> donors(const mesh::Mesh& mesh, int s, const std::vector<int>& neighbours,
                        const std::vector<char>& massless) {
  double nearest = -1;
  std::vector<int> out;
  for (int j : neighbours) {
    if (massless[j]) continue;
    const double d = (mesh.nodes[j] - mesh.nodes[s]).norm();
    if (nearest < 0 || d < nearest * (1 - 1e-9)) {
      nearest = d;
      out.clear();
    }
    if (d <= nearest * (1 + 1e-9)) out.push_back(j);
  }
  return out;
}

}  // namespace

std::vector<int> massless_nodes(const model::Model& m) {
  std::vector<int> out;
  if (!midpoint_type(m.time.scheme)) return out;
  for (const model::ContactPair& pair : m.contact) {
    if (pair.enforcement != model::Enforcement::lagrange || pair.impact != model::ImpactMode::located)
      continue;
    for (const std::string& surface : {pair.slave, pair.master}) {  // both sides (§4.6.1)
      const std::vector<int> nodes = m.mesh.surface_nodes(surface);
      out.insert(out.end(), nodes.begin(), nodes.end());
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

solve::SparseMatrix massless_velocity_map(const model::Model& m) {
  const std::vector<int> nodes = massless_nodes(m);
  if (nodes.empty()) return {};
  std::vector<char> massless(m.mesh.node_count(), 0);
  for (int s : nodes) massless[s] = 1;
  const std::vector<std::vector<int>> neighbours = element_neighbours(m.mesh);
  std::vector<Eigen::Triplet<double>> p;
  for (int I = 0; I < m.mesh.node_count(); ++I) {
    if (!massless[I]) {
      for (int k = 0; k < 3; ++k) p.emplace_back(3 * I + k, 3 * I + k, 1.0);
      continue;
    }
    const std::vector<int> from = donors(m.mesh, I, neighbours[I], massless);
    if (from.empty())
      throw std::invalid_argument("impact \"located\": contact surface node " + std::to_string(I) +
                                  " shares no element with a node off the contact surfaces, so its mass has "
                                  "nowhere to go; use impact \"persist\" for this pair");
    for (int j : from)
      for (int k = 0; k < 3; ++k) p.emplace_back(3 * I + k, 3 * j + k, 1.0 / from.size());  // P (§4.6.1)
  }
  solve::SparseMatrix P(3 * m.mesh.node_count(), 3 * m.mesh.node_count());
  P.setFromTriplets(p.begin(), p.end());
  return P;
}

solve::SparseMatrix contact_mass(const model::Model& m, const solve::SparseMatrix& M) {
  const solve::SparseMatrix P = massless_velocity_map(m);
  if (P.size() == 0) return M;
  solve::SparseMatrix modified = P.transpose() * M * P;  // M' = Pᵀ M P (§4.6.1)
  modified.prune(0.0);
  return modified;
}

}  // namespace stoss::contact
