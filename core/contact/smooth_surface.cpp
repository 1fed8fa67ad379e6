#include "core/contact/smooth_surface.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <utility>

namespace stoss::contact {
namespace {

/// A grid slot as a combination of nodes (a ghost is 2 a − b).
using Combination = std::vector<std::pair<int, double>>;
using Grid = std::array<std::array<std::optional<Combination>, 4>, 4>;  ///< grid[i][j], i along ξ¹

Combination node(int id) { return {{id, 1.0}}; }

Combination reflect(const Combination& at, const Combination& inner) {  // 2 at − inner (2.2)
  Combination c;
  for (const auto& [id, w] : at) c.emplace_back(id, 2 * w);
  for (const auto& [id, w] : inner) c.emplace_back(id, -w);
  return c;
}

class Topology {
 public:
  explicit Topology(const std::vector<mesh::Quad>& faces) : faces_(faces) {
    for (size_t f = 0; f < faces.size(); ++f)
      for (int k = 0; k < 4; ++k) {
        edges_[key(faces[f][k], faces[f][(k + 1) % 4])].push_back(static_cast<int>(f));
        node_faces_[faces[f][k]].push_back(static_cast<int>(f));
      }
  }

  /// First violation of the manifold and valence rules, or empty.
  std::string problem() const {
    for (const auto& [edge, list] : edges_) {
      if (list.size() > 2)
        return "edge (" + std::to_string(edge.first) + ", " + std::to_string(edge.second) + ") lies in " +
               std::to_string(list.size()) + " faces (not a manifold surface)";
      if (list.size() == 2 && direction(list[0], edge) == direction(list[1], edge))
        return "faces " + std::to_string(list[0]) + " and " + std::to_string(list[1]) +
               " are oriented inconsistently across edge (" + std::to_string(edge.first) + ", " +
               std::to_string(edge.second) + ")";
    }
    for (const auto& [id, list] : node_faces_) {
      const bool rim = on_rim(id);
      if (!rim && list.size() != 4)
        return "node " + std::to_string(id) + " lies in " + std::to_string(list.size()) +
               " faces (an extraordinary vertex; the smooth surface needs 4)";
      if (rim && list.size() > 2)
        return "rim node " + std::to_string(id) + " lies in " + std::to_string(list.size()) +
               " faces (the smooth surface needs 1 or 2 at a rim)";
    }
    return {};
  }

  /// The face other than f across edge (a, b), or −1 at a rim.
  int across(int f, int a, int b) const {
    for (int g : edges_.at(key(a, b)))
      if (g != f) return g;
    return -1;
  }

  /// The node of face g next to `at` that is not `other`.
  int next_to(int g, int at, int other) const {
    const mesh::Quad& q = faces_[g];
    const int k = static_cast<int>(std::find(q.begin(), q.end(), at) - q.begin());
    const int before = q[(k + 3) % 4], after = q[(k + 1) % 4];
    return before == other ? after : before;
  }

  /// The fourth node of the face (not f) that holds `corner`, `a` and `b`, if any.
  std::optional<int> diagonal(int f, int corner, int a, int b) const {
    for (int g : node_faces_.at(corner)) {
      if (g == f) continue;
      const mesh::Quad& q = faces_[g];
      const auto has = [&q](int id) { return std::find(q.begin(), q.end(), id) != q.end(); };
      if (!has(a) || !has(b)) continue;
      for (int id : q)
        if (id != corner && id != a && id != b) return id;
    }
    return std::nullopt;
  }

 private:
  static std::pair<int, int> key(int a, int b) { return {std::min(a, b), std::max(a, b)}; }
  int direction(int f, const std::pair<int, int>& edge) const {
    const mesh::Quad& q = faces_[f];
    for (int k = 0; k < 4; ++k)
      if (q[k] == edge.first && q[(k + 1) % 4] == edge.second) return 1;
    return -1;
  }
  bool on_rim(int id) const {
    for (int f : node_faces_.at(id))
      for (int k = 0; k < 4; ++k) {
        const int a = faces_[f][k], b = faces_[f][(k + 1) % 4];
        if ((a == id || b == id) && edges_.at(key(a, b)).size() == 1) return true;
      }
    return false;
  }

  const std::vector<mesh::Quad>& faces_;
  std::map<std::pair<int, int>, std::vector<int>> edges_;
  std::map<int, std::vector<int>> node_faces_;
};

/// Real nodes of the 4×4 grid of face f: the face at slots (1..2)², its edge neighbours, and the
/// diagonal neighbours at the corners (docs/smooth_master_surface.md §2.2).
Grid real_grid(const Topology& t, const std::vector<mesh::Quad>& faces, int f) {
  const mesh::Quad& q = faces[f];
  Grid g;
  g[1][1] = node(q[0]), g[2][1] = node(q[1]), g[2][2] = node(q[2]), g[1][2] = node(q[3]);
  // Edge k from q[k] to q[k+1]; slots beyond it for q[k] and for q[k+1].
  const int beyond[4][2][2] = {{{1, 0}, {2, 0}}, {{3, 1}, {3, 2}}, {{2, 3}, {1, 3}}, {{0, 2}, {0, 1}}};
  for (int k = 0; k < 4; ++k) {
    const int a = q[k], b = q[(k + 1) % 4], other = t.across(f, a, b);
    if (other < 0) continue;
    g[beyond[k][0][0]][beyond[k][0][1]] = node(t.next_to(other, a, b));
    g[beyond[k][1][0]][beyond[k][1][1]] = node(t.next_to(other, b, a));
  }
  // Corner slot of q[k] and the two edge slots next to it.
  const int corner[4][3][2] = {{{0, 0}, {1, 0}, {0, 1}}, {{3, 0}, {2, 0}, {3, 1}},
                               {{3, 3}, {3, 2}, {2, 3}}, {{0, 3}, {0, 2}, {1, 3}}};
  for (int k = 0; k < 4; ++k) {
    const auto& s = corner[k];
    const auto& a = g[s[1][0]][s[1][1]];
    const auto& b = g[s[2][0]][s[2][1]];
    if (!a || !b) continue;
    if (const auto d = t.diagonal(f, q[k], a->front().first, b->front().first)) g[s[0][0]][s[0][1]] = node(*d);
  }
  return g;
}

/// Fills the rim slots by reflection (2.2): rows and columns beyond a rim edge first; then a missing
/// corner across the rim that passes it (the slot the face beyond the other edge reflects too).
void add_ghosts(Grid& g) {
  const bool bottom = !g[1][0], top = !g[1][3];
  for (int m : {1, 2}) {
    if (!g[m][0]) g[m][0] = reflect(*g[m][1], *g[m][2]);
    if (!g[m][3]) g[m][3] = reflect(*g[m][2], *g[m][1]);
    if (!g[0][m]) g[0][m] = reflect(*g[1][m], *g[2][m]);
    if (!g[3][m]) g[3][m] = reflect(*g[2][m], *g[1][m]);
  }
  if (!g[0][0]) g[0][0] = bottom ? reflect(*g[0][1], *g[0][2]) : reflect(*g[1][0], *g[2][0]);
  if (!g[3][0]) g[3][0] = bottom ? reflect(*g[3][1], *g[3][2]) : reflect(*g[2][0], *g[1][0]);
  if (!g[3][3]) g[3][3] = top ? reflect(*g[3][2], *g[3][1]) : reflect(*g[2][3], *g[1][3]);
  if (!g[0][3]) g[0][3] = top ? reflect(*g[0][2], *g[0][1]) : reflect(*g[1][3], *g[2][3]);
}

TensorPatch patch_from_grid(const Grid& g, int reference) {
  TensorPatch p;
  p.family = PatchFamily::cubic_bspline;
  p.nodes.push_back(reference);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i)
      for (const auto& [id, w] : *g[i][j])
        if (std::find(p.nodes.begin(), p.nodes.end(), id) == p.nodes.end()) p.nodes.push_back(id);
  p.weights = Eigen::MatrixXd::Zero(p.size(), 16);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i)
      for (const auto& [id, w] : *g[i][j]) {
        const int K = static_cast<int>(std::find(p.nodes.begin(), p.nodes.end(), id) - p.nodes.begin());
        p.weights(K, i + 4 * j) += w;
      }
  return p;
}

}  // namespace

SmoothSurface smooth_surface(const std::vector<mesh::Quad>& faces) {
  SmoothSurface s;
  const Topology t(faces);
  s.problem = t.problem();
  if (!s.ok()) return s;
  for (size_t f = 0; f < faces.size(); ++f) {
    Grid g = real_grid(t, faces, static_cast<int>(f));
    add_ghosts(g);
    s.patches.push_back(patch_from_grid(g, faces[f][0]));
  }
  return s;
}

std::vector<TensorPatch> faceted_patches(const std::vector<mesh::Quad>& faces) {
  std::vector<TensorPatch> patches;
  for (const mesh::Quad& q : faces) patches.push_back(bilinear_patch(q));
  return patches;
}

}  // namespace stoss::contact
