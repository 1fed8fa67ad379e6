#include "core/loads/held_bodies.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace stoss::loads {
namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// A held body's smallest eigenvalue of G (5b.9), relative to its largest: below it a mode counts as free.
constexpr double free_threshold = 1e-10;

struct BodyFrame {
  Eigen::Vector3d centroid;
  double size;  ///< largest distance of a node from the centroid: scales rotations to lengths
};

BodyFrame frame_of(const mesh::Mesh& mesh, const mesh::Body& body) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int I = body.node_begin; I < body.node_end; ++I) c += mesh.nodes[I];
  c /= std::max(1, body.node_end - body.node_begin);
  double size = 0;
  for (int I = body.node_begin; I < body.node_end; ++I) size = std::max(size, (mesh.nodes[I] - c).norm());
  return {c, size > 0 ? size : 1.0};
}

/// d·φ_j(X) for the six unit modes φ_j: translations e_j, rotations e_j × (X − c)/size (5b.9).
Vector6 constraint_row(const BodyFrame& f, const Eigen::Vector3d& X, const Eigen::Vector3d& d) {
  Vector6 row;
  row.head<3>() = d;
  row.tail<3>() = ((X - f.centroid) / f.size).cross(d);  // d·(e_j × r) = e_j·(r × d)
  return row;
}

/// Reduced row echelon form of the rows of B (r × 6), partial pivoting; tiny entries set to 0.
Eigen::MatrixXd echelon(Eigen::MatrixXd B) {
  int row = 0;
  for (int col = 0; col < 6 && row < B.rows(); ++col) {
    Eigen::Index pivot;
    if (B.col(col).tail(B.rows() - row).cwiseAbs().maxCoeff(&pivot) < 1e-9) continue;
    B.row(row).swap(B.row(row + pivot));
    B.row(row) /= B(row, col);
    for (Eigen::Index r = 0; r < B.rows(); ++r)
      if (r != row) B.row(r) -= B(r, col) * B.row(row);
    ++row;
  }
  return B.unaryExpr([](double x) { return std::abs(x) < 1e-9 ? 0.0 : x; });
}

/// The null space of G = Σ rows rowsᵀ as rigid modes (rotations back in 1/length units).
std::vector<RigidMode> null_modes(const Matrix6& G, const BodyFrame& f) {
  const Eigen::SelfAdjointEigenSolver<Matrix6> eigen(G);
  const double largest = eigen.eigenvalues().maxCoeff();
  std::vector<int> free;
  for (int k = 0; k < 6; ++k)
    if (!(eigen.eigenvalues()[k] > free_threshold * largest)) free.push_back(k);
  if (free.empty()) return {};
  Eigen::MatrixXd basis(free.size(), 6);
  for (size_t k = 0; k < free.size(); ++k) basis.row(k) = eigen.eigenvectors().col(free[k]).transpose();
  const Eigen::MatrixXd rows = echelon(basis);
  std::vector<RigidMode> out;
  for (Eigen::Index k = 0; k < rows.rows(); ++k)
    out.push_back({rows.row(k).head<3>().transpose(), rows.row(k).tail<3>().transpose() / f.size});
  return out;
}

/// The body a surface belongs to. @throws std::out_of_range naming the surface or body the mesh lacks.
int body_of(const mesh::Mesh& mesh, const std::string& body_slash_surface) {
  mesh.surface(body_slash_surface);
  return mesh.find_body(body_slash_surface.substr(0, body_slash_surface.find('/')));
}

/// The surface's nodes along its reference normals (area-weighted over the faces at each node); only the
/// nodes `touching` marks, when it is not empty.
std::vector<HeldDirection> normal_directions(const mesh::Mesh& mesh, const std::string& surface,
                                             const std::vector<char>& touching) {
  std::vector<HeldDirection> out;
  std::vector<int> position(mesh.node_count(), -1);
  for (const mesh::Quad& q : mesh.surface(surface)) {
    const auto& X = mesh.nodes;
    const Eigen::Vector3d area =
        0.5 * (X[q[2]] - X[q[0]]).cross(X[q[3]] - X[q[1]]);  // the face's vector area
    for (int node : q) {
      if (!touching.empty() && !touching[node]) continue;
      if (position[node] < 0) position[node] = static_cast<int>(out.size()), out.push_back({node, {0, 0, 0}});
      out[position[node]].direction += area;
    }
  }
  return out;
}

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", std::abs(x) < 1e-12 ? 0.0 : x);
  return text;
}

std::string point(const Eigen::Vector3d& p) {
  std::string out = "(";
  for (int k = 0; k < 3; ++k) out.append(k ? ", " : "").append(number(p[k]));
  return out.append(")");
}

/// "x", "y", "z" for a coordinate axis, else the unit vector.
std::string axis(const Eigen::Vector3d& v) {
  const Eigen::Vector3d u = v.normalized();
  for (int k = 0; k < 3; ++k)
    if (std::abs(std::abs(u[k]) - 1) < 1e-9) return std::string(1, char('x' + k));
  return point(u);
}

}  // namespace

std::vector<BodyFreedom> free_rigid_modes(const mesh::Mesh& mesh, const std::vector<char>& fixed,
                                          const std::vector<HeldDirection>& extra) {
  std::vector<Matrix6> G(mesh.bodies.size(), Matrix6::Zero());
  std::vector<BodyFrame> frames;
  std::vector<int> body_of_node(mesh.node_count(), 0);
  for (size_t b = 0; b < mesh.bodies.size(); ++b) {
    frames.push_back(frame_of(mesh, mesh.bodies[b]));
    for (int I = mesh.bodies[b].node_begin; I < mesh.bodies[b].node_end; ++I) body_of_node[I] = int(b);
  }
  auto hold = [&](int node, const Eigen::Vector3d& d) {
    const Vector6 row = constraint_row(frames[body_of_node[node]], mesh.nodes[node], d);
    G[body_of_node[node]] += row * row.transpose();  // (5b.9)
  };
  for (int I = 0; I < mesh.node_count(); ++I)
    for (int k = 0; k < 3; ++k)
      if (fixed[3 * I + k]) hold(I, Eigen::Vector3d::Unit(k));
  for (const HeldDirection& h : extra)
    if (h.direction.norm() > 0) hold(h.node, h.direction.normalized());
  std::vector<BodyFreedom> out;
  for (size_t b = 0; b < mesh.bodies.size(); ++b)
    out.push_back({int(b), frames[b].centroid, null_modes(G[b], frames[b])});
  return out;
}

std::vector<BodyFreedom> free_rigid_modes(const mesh::Mesh& mesh, const std::vector<char>& fixed,
                                          const std::vector<ContactSurfaces>& contact) {
  std::vector<HeldDirection> extra;
  std::vector<char> applied(2 * contact.size(), 0);  ///< per pair: slave side, master side
  std::vector<BodyFreedom> freedom = free_rigid_modes(mesh, fixed, extra);
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t p = 0; p < contact.size(); ++p) {
      const int slave = body_of(mesh, contact[p].slave), master = body_of(mesh, contact[p].master.at(0));
      const bool slave_held = freedom.at(slave).held(), master_held = freedom.at(master).held();
      for (int side = 0; side < 2; ++side) {
        const bool other_held = side == 0 ? master_held : slave_held,
                   this_held = side == 0 ? slave_held : master_held;
        if (applied[2 * p + side] || !other_held || this_held) continue;
        applied[2 * p + side] = changed = true;
        for (const std::string& surface :
             side == 0 ? std::vector<std::string>{contact[p].slave} : contact[p].master)
          for (const HeldDirection& h : normal_directions(mesh, surface, contact[p].touching))
            extra.push_back(h);
      }
    }
    if (changed) freedom = free_rigid_modes(mesh, fixed, extra);
  }
  return freedom;
}

std::string describe(const RigidMode& mode, const Eigen::Vector3d& centroid) {
  const double t = mode.translation.norm(), w = mode.rotation.norm();
  if (w == 0) return "translation along " + axis(mode.translation);
  const Eigen::Vector3d through = centroid + mode.rotation.cross(mode.translation) / (w * w);
  const double along = mode.translation.dot(mode.rotation) / w;
  const std::string rotation = "rotation about " + axis(mode.rotation) + " through " + point(through);
  if (t == 0 || std::abs(along) <= 1e-9 * t) return rotation;
  return rotation + " with translation " + number(along / w) + " per radian along it";
}

std::string rigid_mode_rule(const mesh::Mesh& mesh, const BodyFreedom& freedom) {
  if (freedom.held()) return "";
  std::string modes;
  for (const RigidMode& m : freedom.free_modes)
    modes += (modes.empty() ? "" : ", ") + describe(m, freedom.centroid);
  return "body '" + mesh.bodies.at(freedom.body).name + "' is free to move as a rigid body (" + modes +
         "): a static scene needs supports, prescribed motions or contacts with held bodies that remove "
         "every "
         "rigid mode";
}

}  // namespace stoss::loads
