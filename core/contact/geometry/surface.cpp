#include "core/contact/geometry/surface.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace stoss::contact {
namespace {

double mean_edge_length(const mesh::Quad& q, const std::vector<Eigen::Vector3d>& X) {
  double sum = 0;
  for (int k = 0; k < 4; ++k) sum += (X[q[(k + 1) % 4]] - X[q[k]]).norm();
  return sum / 4;
}

/// Area of a (possibly warped) quad from its two diagonals: ½ |(c − a) × (d − b)|.
double quad_area(const mesh::Quad& q, const std::vector<Eigen::Vector3d>& X) {
  return 0.5 * (X[q[2]] - X[q[0]]).cross(X[q[3]] - X[q[1]]).norm();
}

std::vector<double> tributary_areas(const std::vector<int>& nodes, const std::vector<mesh::Quad>& quads,
                                    const std::vector<Eigen::Vector3d>& X) {
  std::vector<double> area(nodes.size(), 0.0);
  for (const mesh::Quad& q : quads) {
    const double quarter = quad_area(q, X) / 4;
    for (int node : q) {
      const auto it = std::lower_bound(nodes.begin(), nodes.end(), node);
      area[it - nodes.begin()] += quarter;
    }
  }
  return area;
}

}  // namespace

PairSurfaces pair_surfaces(const mesh::Mesh& mesh, const std::string& slave, const std::string& master) {
  PairSurfaces s;
  s.slave_nodes = mesh.surface_nodes(slave);
  s.faces = mesh.surface(master);
  if (s.slave_nodes.empty()) throw std::invalid_argument("contact slave surface '" + slave + "' is empty");
  if (s.faces.empty()) throw std::invalid_argument("contact master surface '" + master + "' is empty");
  s.tributary_area = tributary_areas(s.slave_nodes, mesh.surface(slave), mesh.nodes);
  for (const mesh::Quad& q : s.faces) s.face_size.push_back(mean_edge_length(q, mesh.nodes));
  s.mean_face_size = std::accumulate(s.face_size.begin(), s.face_size.end(), 0.0) / s.faces.size();
  return s;
}

std::vector<int> master_nodes(const PairSurfaces& s, int face) {
  if (s.smooth()) return s.patches[face].nodes;
  return {s.faces[face].begin(), s.faces[face].end()};
}

std::vector<int> element_dofs(int slave, const PairSurfaces& s, int face) {
  std::vector<int> dofs = {3 * slave, 3 * slave + 1, 3 * slave + 2};
  for (int node : master_nodes(s, face))
    for (int k = 0; k < 3; ++k) dofs.push_back(3 * node + k);
  return dofs;
}

SegmentNodes face_positions(const mesh::Quad& face, const Eigen::VectorXd& x) {
  SegmentNodes y;
  for (int K = 0; K < 4; ++K) y.row(K) = x.segment<3>(3 * face[K]).transpose();
  return y;
}

std::array<int, 15> element_dofs(int slave, const mesh::Quad& face) {
  std::array<int, 15> dofs;
  for (int k = 0; k < 3; ++k) dofs[k] = 3 * slave + k;
  for (int K = 0; K < 4; ++K)
    for (int k = 0; k < 3; ++k) dofs[3 + 3 * K + k] = 3 * face[K] + k;
  return dofs;
}

Vector15 element_positions(int slave, const mesh::Quad& face, const Eigen::VectorXd& x) {
  return element_vector(x.segment<3>(3 * slave), face_positions(face, x));
}

}  // namespace stoss::contact
