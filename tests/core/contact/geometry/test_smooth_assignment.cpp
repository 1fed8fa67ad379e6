// On the smooth master surface every slave node in the contact zone — within one master face size of
// the surface — shall find a surface point, at the globally closest place (docs/smooth_master_surface.md
// §3.1): checked against a brute-force search over every patch near the node (sampled, then polished
// by the patch CPP). Scene: two hollow balls interpenetrating off-centre (convex on convex, the master's
// extraordinary vertices included), the geometry of api/examples/two_balls.json at contact. On the
// faceted surface the same nodes show the NTS blind spot.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "core/contact/geometry/assignment.hpp"
#include "core/contact/geometry/broad_phase.hpp"
#include "core/contact/geometry/patch_projection.hpp"
#include "core/contact/geometry/smooth_surface.hpp"
#include "core/mesh/generators.hpp"

namespace stoss::contact {
namespace {

struct TwoBalls {
  mesh::Mesh mesh;
  PairSurfaces s;
  Eigen::VectorXd x;
  BroadPhase broad;
  explicit TwoBalls(bool smooth) {
    // The master ball turned so that one of its cube corners (an extraordinary vertex) faces the slave.
    const Eigen::Matrix3d turn = (Eigen::AngleAxisd(0.6155, Eigen::Vector3d::UnitY()) *
                                  Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitZ()))
                                     .toRotationMatrix();
    mesh::BodyMesh master = mesh::hollow_sphere({0, 0, 0}, 1.0, 0.8, 6, 2);
    for (Eigen::Vector3d& X : master.nodes) X = turn * X + Eigen::Vector3d(0.9, 0.25, 0.1);
    mesh.add_body("left", mesh::hollow_sphere({-0.97, -0.25, 0}, 1.0, 0.8, 6, 2));
    mesh.add_body("right", master);
    s = pair_surfaces(mesh, "left/outer", "right/outer");
    if (smooth) s.patches = smooth_surface(s.faces).patches;
    x = mesh.reference_positions();
    broad.update(s, x, x);
  }
  Eigen::Vector3d slave(int i) const { return x.segment<3>(3 * s.slave_nodes[i]); }
};

/// The signed gap of the closest surface point over the patches near p: 21 × 21 samples per patch,
/// the best polished by the CPP on its patch; sign from the normal there.
double brute_force_gap(const TwoBalls& b, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity(), gap = 0;
  for (size_t f = 0; f < b.s.faces.size(); ++f) {
    if ((b.x.segment<3>(3 * b.s.faces[f][0]) - p).norm() > 3 * b.s.mean_face_size) continue;
    const TensorPatch& patch = b.s.patches[f];
    Eigen::Vector2d best_xi(0, 0);
    double sample = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= 20; ++i)
      for (int j = 0; j <= 20; ++j) {
        const Eigen::Vector2d xi(-1 + i / 10.0, -1 + j / 10.0);
        const double d = (p - patch_frame(patch, b.x, xi).y).norm();
        if (d < sample) sample = d, best_xi = xi;
      }
    const Projection polished = patch_projection(p, patch, b.x, best_xi);
    const bool on_patch = polished.converged && inside(polished.xi, 1e-9);
    const double d = on_patch ? std::abs(polished.gap) : sample;
    if (d < best) best = d, gap = on_patch ? polished.gap : sample;
  }
  return gap;
}

TEST(SmoothAssignment, EveryNodeInTheContactZoneFindsTheClosestSurfacePoint) {
  const TwoBalls b(true);
  int zone = 0, checked_near_vertex = 0;
  for (int i : b.broad.near_slaves()) {
    const Eigen::Vector3d p = b.slave(i);
    const double expected = brute_force_gap(b, p);
    if (std::abs(expected) > b.s.mean_face_size) continue;  // outside the contact zone
    ++zone;
    const FaceProjection found = best_face(p, b.broad.candidates(i), b.s, b.x);
    ASSERT_TRUE(found.found()) << "slave node " << b.s.slave_nodes[i] << " at gap " << expected;
    EXPECT_NEAR(found.projection.gap, expected, 1e-9 * b.s.mean_face_size)
        << "slave node " << b.s.slave_nodes[i];
    checked_near_vertex += b.s.patches[found.face].pieces != nullptr;
  }
  EXPECT_GT(zone, 10) << "the balls overlap over a patch of slave nodes";
  EXPECT_GT(checked_near_vertex, 0) << "some nodes project onto faces at the extraordinary vertex";
  std::printf("smooth: %d slave nodes in the contact zone, %d on extraordinary faces, all projected\n", zone,
              checked_near_vertex);
}

TEST(SmoothAssignment, TheFacetedSurfaceLeavesBlindSpotsOnTheSameNodes) {
  const TwoBalls smooth(true), faceted(false);
  int zone = 0, blind = 0;
  for (int i : faceted.broad.near_slaves()) {
    if (std::abs(brute_force_gap(smooth, smooth.slave(i))) > smooth.s.mean_face_size) continue;
    ++zone;
    blind += !best_face(faceted.slave(i), faceted.broad.candidates(i), faceted.s, faceted.x).found();
  }
  EXPECT_GT(blind, 0) << "convex faceted edges: some nodes of the zone project onto no face";
  std::printf("faceted: %d of %d slave nodes in the contact zone project onto no face\n", blind, zone);
}

}  // namespace
}  // namespace stoss::contact
