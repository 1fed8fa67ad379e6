#include "core/contact/geometry/smooth_surface.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>

namespace stoss::contact {
namespace {

/// A grid slot as a combination of nodes (a ghost is 2 a − b).
using Combination = std::vector<std::pair<int, double>>;
using Grid = std::array<std::array<std::optional<Combination>, 4>, 4>;  ///< grid[i][j], i along ξ¹

Combination node(int id) {
  return {{id, 1.0}};
}

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
      if (!rim && list.size() < 3)
        return "node " + std::to_string(id) + " lies in " + std::to_string(list.size()) +
               " faces without being on a rim (a degenerate surface)";
      if (rim && list.size() > 2)
        return "rim node " + std::to_string(id) + " lies in " + std::to_string(list.size()) +
               " faces (the smooth surface needs 1 or 2 at a rim)";
    }
    for (size_t f = 0; f < faces_.size(); ++f) {
      std::vector<int> corners;
      bool rim = false;
      for (int id : faces_[f]) {
        if (extraordinary(id)) corners.push_back(id);
        rim = rim || on_rim(id);
      }
      if (corners.size() > 1)
        return "face " + std::to_string(f) + " has extraordinary vertices at nodes " +
               std::to_string(corners[0]) + " and " + std::to_string(corners[1]) +
               " (at most one per face; refine the mesh)";
      if (!corners.empty() && rim)
        return "extraordinary vertex " + std::to_string(corners[0]) + " lies on a face that touches the rim";
    }
    return {};
  }

  /// An interior node in other than four faces (Catmull–Clark's extraordinary vertex).
  bool extraordinary(int id) const { return node_faces_.at(id).size() != 4 && !on_rim(id); }
  const std::vector<int>& faces_at(int id) const { return node_faces_.at(id); }

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
  const int corner[4][3][2] = {
      {{0, 0}, {1, 0}, {0, 1}}, {{3, 0}, {2, 0}, {3, 1}}, {{3, 3}, {3, 2}, {2, 3}}, {{0, 3}, {0, 2}, {1, 3}}};
  for (int k = 0; k < 4; ++k) {
    const auto& s = corner[k];
    const auto& a = g[s[1][0]][s[1][1]];
    const auto& b = g[s[2][0]][s[2][1]];
    if (!a || !b) continue;
    if (const auto d = t.diagonal(f, q[k], a->front().first, b->front().first))
      g[s[0][0]][s[0][1]] = node(*d);
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

/// A small quad mesh whose vertex values are weights over a patch's nodes (NaN: not determined by
/// them), for Catmull–Clark steps near an extraordinary vertex (2.5).
struct LocalMesh {
  std::vector<mesh::Quad> faces;
  std::vector<Eigen::VectorXd> values;
};

/// One Catmull–Clark step (2.5). Face points: the mean of the face's vertices; edge points: the mean
/// of the edge's ends and its two face points (NaN on the mesh's border); vertex points:
/// (Q + 2R + (n − 3) v)/n with Q the mean face point, R the mean edge midpoint of the n faces and
/// edges around v (NaN on the border). children[k] is the child at corner k of face f, ordered to
/// keep f's axes: [V0, E01, F, E30], [E01, V1, E12, F], [F, E12, V2, E23], [E30, F, E23, V3].
LocalMesh subdivide(const LocalMesh& m, int f, std::array<int, 4>& children) {
  const int nf = static_cast<int>(m.faces.size()), nv = static_cast<int>(m.values.size());
  std::map<std::pair<int, int>, int> edge_id;
  std::vector<std::pair<int, int>> edges;
  std::vector<std::vector<int>> edge_faces, vertex_faces(nv), vertex_edges(nv);
  for (int g = 0; g < nf; ++g)
    for (int k = 0; k < 4; ++k) {
      const int a = m.faces[g][k], b = m.faces[g][(k + 1) % 4];
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto [it, fresh] = edge_id.try_emplace(key, static_cast<int>(edges.size()));
      if (fresh) {
        edges.push_back(key);
        edge_faces.emplace_back();
        vertex_edges[a].push_back(it->second);
        vertex_edges[b].push_back(it->second);
      }
      edge_faces[it->second].push_back(g);
      vertex_faces[a].push_back(g);
    }
  const int ne = static_cast<int>(edges.size());
  const Eigen::Index M = m.values.front().size();
  const Eigen::VectorXd unknown = Eigen::VectorXd::Constant(M, std::numeric_limits<double>::quiet_NaN());
  LocalMesh out;
  out.values.resize(nf + ne + nv, unknown);
  for (int g = 0; g < nf; ++g) {
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(M);
    for (int id : m.faces[g]) sum += m.values[id];
    out.values[g] = sum / 4;  // (2.5) face point
  }
  for (int e = 0; e < ne; ++e)
    if (edge_faces[e].size() == 2)  // (2.5) edge point
      out.values[nf + e] = (m.values[edges[e].first] + m.values[edges[e].second] +
                            out.values[edge_faces[e][0]] + out.values[edge_faces[e][1]]) /
                           4;
  for (int v = 0; v < nv; ++v) {
    const int n = static_cast<int>(vertex_faces[v].size());
    const bool interior = n == static_cast<int>(vertex_edges[v].size()) &&
                          std::all_of(vertex_edges[v].begin(), vertex_edges[v].end(),
                                      [&](int e) { return edge_faces[e].size() == 2; });
    if (!interior) continue;
    Eigen::VectorXd Q = Eigen::VectorXd::Zero(M), R = Eigen::VectorXd::Zero(M);
    for (int g : vertex_faces[v]) Q += out.values[g] / n;
    for (int e : vertex_edges[v]) R += (m.values[edges[e].first] + m.values[edges[e].second]) / (2 * n);
    out.values[nf + ne + v] = (Q + 2 * R + (n - 3) * m.values[v]) / n;  // (2.5) vertex point
  }
  const auto edge_point = [&](int a, int b) { return nf + edge_id.at({std::min(a, b), std::max(a, b)}); };
  for (int g = 0; g < nf; ++g) {
    const mesh::Quad& q = m.faces[g];
    for (int k = 0; k < 4; ++k) {
      mesh::Quad child{nf + ne + q[k], edge_point(q[k], q[(k + 1) % 4]), g, edge_point(q[(k + 3) % 4], q[k])};
      if (g == f) {  // keep f's axes: rotate child k to start at its corner nearest f's corner 0
        std::rotate(child.begin(), child.begin() + (4 - k) % 4, child.end());
        children[k] = static_cast<int>(out.faces.size());
      }
      out.faces.push_back(child);
    }
  }
  return out;
}

/// The faces of m that share a vertex with face c, renumbered; c's new index in `c`.
LocalMesh one_ring(const LocalMesh& m, int& c) {
  LocalMesh out;
  std::map<int, int> renumber;
  const auto id = [&](int v) {
    auto [it, fresh] = renumber.try_emplace(v, static_cast<int>(out.values.size()));
    if (fresh) out.values.push_back(m.values[v]);
    return it->second;
  };
  const mesh::Quad& centre = m.faces[c];
  int new_c = -1;
  for (size_t g = 0; g < m.faces.size(); ++g) {
    const mesh::Quad& q = m.faces[g];
    if (std::none_of(q.begin(), q.end(),
                     [&](int v) { return std::find(centre.begin(), centre.end(), v) != centre.end(); }))
      continue;
    if (static_cast<int>(g) == c) new_c = static_cast<int>(out.faces.size());
    out.faces.push_back({id(q[0]), id(q[1]), id(q[2]), id(q[3])});
  }
  c = new_c;
  return out;
}

Grid real_grid(const Topology& t, const std::vector<mesh::Quad>& faces, int f);

/// The piece of a subdivided local mesh at child face c: its 4×4 grid's values as slot weights.
TensorPatch piece(const LocalMesh& m, int c, const std::vector<int>& nodes) {
  const Topology t(m.faces);
  const Grid g = real_grid(t, m.faces, c);
  TensorPatch p;
  p.family = PatchFamily::cubic_bspline;
  p.nodes = nodes;
  p.weights.resize(static_cast<Eigen::Index>(nodes.size()), 16);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      if (!g[i][j]) throw std::logic_error("Catmull–Clark piece without a 4×4 neighbourhood");
      p.weights.col(i + 4 * j) = m.values[g[i][j]->front().first];
      if (!p.weights.col(i + 4 * j).allFinite())
        throw std::logic_error("Catmull–Clark piece beyond its 1-ring");
    }
  return p;
}

/// The Catmull–Clark limit surface of face f whose corner k is extraordinary, as rings of regular
/// pieces (2.5): the face's 1-ring, subdivided `rings` times towards the vertex.
TensorPatch extraordinary_patch(const Topology& t, const std::vector<mesh::Quad>& faces, int f, int k) {
  mesh::Quad q = faces[f];
  std::rotate(q.begin(), q.begin() + k, q.end());  // the vertex first
  std::vector<int> nodes;
  const auto local = [&](int id) {
    const auto it = std::find(nodes.begin(), nodes.end(), id);
    if (it != nodes.end()) return static_cast<int>(it - nodes.begin());
    nodes.push_back(id);
    return static_cast<int>(nodes.size()) - 1;
  };
  LocalMesh m;
  int centre = -1;
  std::vector<int> ring;
  for (int id : q)
    for (int g : t.faces_at(id))
      if (std::find(ring.begin(), ring.end(), g) == ring.end()) ring.push_back(g);
  for (int g : ring) {
    const mesh::Quad& face = g == f ? q : faces[g];
    if (g == f) centre = static_cast<int>(m.faces.size());
    m.faces.push_back({local(face[0]), local(face[1]), local(face[2]), local(face[3])});
  }
  for (size_t K = 0; K < nodes.size(); ++K) m.values.push_back(Eigen::VectorXd::Unit(nodes.size(), K));
  auto pieces = std::make_shared<ExtraordinaryPieces>();
  pieces->corner = k;
  constexpr int rings = 24;  // the innermost ring spans 2⁻²⁴ of the face
  for (int n = 1; n <= rings; ++n) {
    std::array<int, 4> children{};
    const LocalMesh s = subdivide(m, centre, children);
    pieces->rings.push_back(
        {piece(s, children[1], nodes), piece(s, children[2], nodes), piece(s, children[3], nodes)});
    centre = children[0];
    m = one_ring(s, centre);
  }
  TensorPatch p;
  p.family = PatchFamily::cubic_bspline;
  p.nodes = nodes;
  p.pieces = std::move(pieces);
  return p;
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
    const mesh::Quad& q = faces[f];
    const auto corner = std::find_if(q.begin(), q.end(), [&t](int id) { return t.extraordinary(id); });
    if (corner != q.end()) {
      s.patches.push_back(
          extraordinary_patch(t, faces, static_cast<int>(f), static_cast<int>(corner - q.begin())));
      continue;
    }
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
