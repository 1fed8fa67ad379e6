#include "core/mesh/generators.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace stoss::mesh {
namespace {

enum Face { zeta_minus, zeta_plus, eta_minus, eta_plus, xi_minus, xi_plus };  // order of hex_faces

void add_face(BodyMesh& m, const char* surface, const Hex& h, Face f) {
  m.surfaces[surface].push_back(hex_faces(h)[f]);
}

void add_box_faces(BodyMesh& m, const Hex& h, const std::array<int, 3>& ijk, const std::array<int, 3>& n) {
  if (ijk[0] == 0) add_face(m, "xmin", h, xi_minus);
  if (ijk[0] == n[0] - 1) add_face(m, "xmax", h, xi_plus);
  if (ijk[1] == 0) add_face(m, "ymin", h, eta_minus);
  if (ijk[1] == n[1] - 1) add_face(m, "ymax", h, eta_plus);
  if (ijk[2] == 0) add_face(m, "bottom", h, zeta_minus);
  if (ijk[2] == n[2] - 1) add_face(m, "top", h, zeta_plus);
}

/// Finds a node within `tolerance` (max-norm) of a point, or appends it: a hash grid of cell size
/// `tolerance`, so a match can only sit in the 27 cells around the point's own.
class NodeMerger {
 public:
  NodeMerger(std::vector<Eigen::Vector3d>& nodes, const Eigen::Vector3d& origin, double tolerance)
      : nodes_(nodes), origin_(origin), tolerance_(tolerance) {}

  int index_of(const Eigen::Vector3d& x) {
    const Cell c = cell_of(x);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == cells_.end()) continue;
          for (int n : it->second)
            if ((nodes_[n] - x).lpNorm<Eigen::Infinity>() <= tolerance_) return n;
        }
    nodes_.push_back(x);
    cells_[c].push_back(static_cast<int>(nodes_.size()) - 1);
    return static_cast<int>(nodes_.size()) - 1;
  }

 private:
  using Cell = std::array<long long, 3>;
  struct CellHash {
    size_t operator()(const Cell& c) const {
      return std::hash<long long>()(c[0]) ^ (std::hash<long long>()(c[1]) * 0x9e3779b97f4a7c15ULL) ^
             (std::hash<long long>()(c[2]) * 0xc2b2ae3d27d4eb4fULL);
    }
  };

  /// The cell index of a scaled coordinate, clamped to ±1e18 (NaN to 0) so that the conversion and
  /// the ±1 neighbours never overflow; the distance test in index_of still decides a match.
  static long long cell_index(double s) {
    constexpr double limit = 1e18;
    if (!(std::abs(s) < limit))
      return s > 0 ? 1'000'000'000'000'000'000LL : s < 0 ? -1'000'000'000'000'000'000LL : 0;
    return static_cast<long long>(std::floor(s));
  }

  Cell cell_of(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d s = (x - origin_) / tolerance_;
    return {cell_index(s[0]), cell_index(s[1]), cell_index(s[2])};
  }

  std::vector<Eigen::Vector3d>& nodes_;
  Eigen::Vector3d origin_;
  double tolerance_;
  std::unordered_map<Cell, std::vector<int>, CellHash> cells_;
};

/// Parameters of one cube-sphere patch (a, σ) of docs/theory.md §7.
struct Patch {
  int a;
  double sigma;
};

/// The direction at angles (α, β) ∈ [−π/4, π/4]² across a patch: normalize(σ e_a + tan α e_b + tan β e_c).
Eigen::Vector3d patch_direction(const Patch& patch, double alpha, double beta) {
  const double u = std::tan(alpha), v = std::tan(beta);
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  p[patch.a] = patch.sigma;  // p = σ e_a + u e_b + v e_c, (a, b, c) cyclic
  p[(patch.a + 1) % 3] = u;
  p[(patch.a + 2) % 3] = v;
  return p.normalized();
}

/// The equiangular direction of grid point (i, j) of d × d.
Eigen::Vector3d patch_direction(const Patch& patch, int i, int j, int divisions) {
  const double quarter = std::numbers::pi / 4, step = std::numbers::pi / (2 * divisions);
  return patch_direction(patch, -quarter + i * step, -quarter + j * step);
}

/// The solid sphere's grading g(s) = sinh(κ s)/sinh(κ) of a grid parameter s ∈ [−1, 1] (docs/theory.md
/// (5b.8)): odd and increasing, g(±1) = ±1, the identity for κ = 0, denser towards s = 0 for κ > 0.
double graded(double s, double kappa) {
  return kappa > 0 ? std::sinh(kappa * s) / std::sinh(kappa) : s;
}

/// The grid parameter −1 + 2i/d.
double grid_parameter(int i, int d) {
  return -1 + 2.0 * i / d;
}

/// The node of cell corner (i, j, k) of a patch: i, j across the patch, k from the inner to the outer layer.
using PatchNode = std::function<Eigen::Vector3d(int i, int j, int k)>;

/// The d × d × layers hexahedra of one patch, ζ pointing outwards; the faces of layer 0 go to `inner`
/// (when named) and those of the last layer to `outer`.
void add_patch(BodyMesh& m, NodeMerger& merger, const Patch& patch, const PatchNode& position, int d,
               int layers, const char* inner, const char* outer) {
  auto id = [&](int i, int j, int k) { return (i * (d + 1) + j) * (layers + 1) + k; };
  std::vector<int> node((d + 1) * (d + 1) * (layers + 1));
  for (int i = 0; i <= d; ++i)
    for (int j = 0; j <= d; ++j)
      for (int k = 0; k <= layers; ++k) node[id(i, j, k)] = merger.index_of(position(i, j, k));
  for (int i = 0; i < d; ++i)
    for (int j = 0; j < d; ++j)
      for (int k = 0; k < layers; ++k) {
        // Bottom quad (i,j),(i+1,j),(i+1,j+1),(i,j+1); for σ = −1 the roles of i and j exchange.
        const int i1 = patch.sigma > 0 ? i + 1 : i, j1 = patch.sigma > 0 ? j : j + 1;
        const int i3 = patch.sigma > 0 ? i : i + 1, j3 = patch.sigma > 0 ? j + 1 : j;
        const Hex h{node[id(i, j, k)],
                    node[id(i1, j1, k)],
                    node[id(i + 1, j + 1, k)],
                    node[id(i3, j3, k)],
                    node[id(i, j, k + 1)],
                    node[id(i1, j1, k + 1)],
                    node[id(i + 1, j + 1, k + 1)],
                    node[id(i3, j3, k + 1)]};
        m.hex8.push_back(h);
        if (inner && k == 0) add_face(m, inner, h, zeta_minus);
        if (k == layers - 1) add_face(m, outer, h, zeta_plus);
      }
}

/// The point (i, j) of the graded d × d grid on the cube face x_a = σ of [−1, 1]³.
Eigen::Vector3d cube_face_point(const Patch& patch, int i, int j, int d, double kappa) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  p[patch.a] = patch.sigma;
  p[(patch.a + 1) % 3] = graded(grid_parameter(i, d), kappa);
  p[(patch.a + 2) % 3] = graded(grid_parameter(j, d), kappa);
  return p;
}

/// The sphere's direction of grid point (i, j): angles π/4 · g(s) (5b.8).
Eigen::Vector3d sphere_direction(const Patch& patch, int i, int j, int d, double kappa) {
  const double quarter = std::numbers::pi / 4;
  return patch_direction(patch, quarter * graded(grid_parameter(i, d), kappa),
                         quarter * graded(grid_parameter(j, d), kappa));
}

/// The hexahedra of the core cube c + h·g([−1, 1]³) (box's node and element order, coordinates graded),
/// merged into m.
void add_core_cube(BodyMesh& m, NodeMerger& merger, const Eigen::Vector3d& center, double half_width, int d,
                   double kappa) {
  const BodyMesh core = box(Eigen::Vector3d::Constant(-1), Eigen::Vector3d::Constant(1), {d, d, d});
  std::vector<int> node;
  node.reserve(core.nodes.size());
  for (const Eigen::Vector3d& s : core.nodes)
    node.push_back(
        merger.index_of(center + half_width * s.unaryExpr([&](double c) { return graded(c, kappa); })));
  for (const Hex& h : core.hex8) {
    Hex g;
    for (int I = 0; I < 8; ++I) g[I] = node[h[I]];
    m.hex8.push_back(g);
  }
}

/// The elements of m with centroid x > c_x and y > c_y, nodes renumbered in their order; surfaces: the
/// boundary faces on the plane x = c_x (`xmin`), on y = c_y (`ymin`), and the rest (`outer`).
BodyMesh quarter_of(const BodyMesh& m, const Eigen::Vector3d& center, double tolerance) {
  BodyMesh out;
  std::vector<int> renumbered(m.nodes.size(), -1);
  for (const Hex& h : m.hex8) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int n : h) centroid += m.nodes[n] / 8;
    if (!(centroid.x() > center.x() && centroid.y() > center.y())) continue;
    out.hex8.push_back(h);
    for (int& n : out.hex8.back()) {
      if (renumbered[n] < 0)
        renumbered[n] = static_cast<int>(out.nodes.size()), out.nodes.push_back(m.nodes[n]);
      n = renumbered[n];
    }
  }
  auto on_plane = [&](const Quad& q, int axis) {
    for (int n : q)
      if (std::abs(out.nodes[n][axis] - center[axis]) > tolerance) return false;
    return true;
  };
  for (const Quad& q : boundary_faces(out.hex8))
    out.surfaces[on_plane(q, 0) ? "xmin" : on_plane(q, 1) ? "ymin" : "outer"].push_back(q);
  return out;
}

}  // namespace

BodyMesh box(const Eigen::Vector3d& min, const Eigen::Vector3d& max, const std::array<int, 3>& n) {
  if (!(max.array() > min.array()).all()) throw std::invalid_argument("box: max must be > min componentwise");
  if (n[0] < 1 || n[1] < 1 || n[2] < 1) throw std::invalid_argument("box: every division must be >= 1");
  BodyMesh m;
  auto id = [&](int i, int j, int k) { return i + (n[0] + 1) * (j + (n[1] + 1) * k); };
  const Eigen::Vector3d size = max - min;
  for (int k = 0; k <= n[2]; ++k)
    for (int j = 0; j <= n[1]; ++j)
      for (int i = 0; i <= n[0]; ++i)
        m.nodes.push_back(min + Eigen::Vector3d(size[0] * i / n[0], size[1] * j / n[1], size[2] * k / n[2]));
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const Hex h{id(i, j, k),     id(i + 1, j, k),     id(i + 1, j + 1, k),     id(i, j + 1, k),
                    id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
        m.hex8.push_back(h);
        add_box_faces(m, h, {i, j, k}, n);
      }
  return m;
}

BodyMesh hollow_sphere(const Eigen::Vector3d& center, double outer_radius, double inner_radius, int divisions,
                       int layers) {
  if (!(inner_radius > 0 && outer_radius > inner_radius))
    throw std::invalid_argument("hollow_sphere: need outer_radius > inner_radius > 0");
  if (divisions < 1 || layers < 1)
    throw std::invalid_argument("hollow_sphere: divisions and layers must be >= 1");
  BodyMesh m;
  NodeMerger merger(m.nodes, center, 1e-9 * outer_radius);
  for (int a = 0; a < 3; ++a)
    for (double sigma : {1.0, -1.0}) {
      const Patch patch{a, sigma};
      const PatchNode position = [&](int i, int j, int k) -> Eigen::Vector3d {
        const double r = inner_radius + k * (outer_radius - inner_radius) / layers;
        return center + r * patch_direction(patch, i, j, divisions);
      };
      add_patch(m, merger, patch, position, divisions, layers, "inner", "outer");
    }
  return m;
}

int sphere_layers(int divisions) {
  return std::max(1, (3 * divisions + 2) / 4);
}

BodyMesh sphere(const Eigen::Vector3d& center, double radius, int divisions, const SphereOptions& options) {
  if (!(radius > 0) || !std::isfinite(radius)) throw std::invalid_argument("sphere: radius must be > 0");
  if (divisions < 1) throw std::invalid_argument("sphere: divisions must be >= 1");
  const double kappa = options.grading;
  if (!(kappa >= 0 && kappa <= 10)) throw std::invalid_argument("sphere: grading must be in [0, 10]");
  if (!(options.radial_grading >= 0 && options.radial_grading <= 10))
    throw std::invalid_argument("sphere: radial_grading must be in [0, 10]");
  if (options.quarter && divisions % 2 != 0)
    throw std::invalid_argument("sphere: a quarter needs even divisions (its cut planes are element faces)");
  const double core = sphere_core_fraction * radius;
  const int d = divisions, layers = sphere_layers(divisions);
  BodyMesh m;
  NodeMerger merger(m.nodes, center, 1e-9 * radius);
  add_core_cube(m, merger, center, core, d, kappa);
  for (int a = 0; a < 3; ++a)
    for (double sigma : {1.0, -1.0}) {
      const Patch patch{a, sigma};
      // A cap: straight lines from the core cube's face to the sphere (docs/theory.md (5b.8)).
      const PatchNode position = [&](int i, int j, int k) -> Eigen::Vector3d {
        const double s = 1 - graded(1 - double(k) / layers, options.radial_grading);  // denser outwards
        return center + (1 - s) * core * cube_face_point(patch, i, j, d, kappa) +
               s * radius * sphere_direction(patch, i, j, d, kappa);
      };
      add_patch(m, merger, patch, position, d, layers, nullptr, "outer");
    }
  return options.quarter ? quarter_of(m, center, 1e-9 * radius) : m;
}

}  // namespace stoss::mesh
