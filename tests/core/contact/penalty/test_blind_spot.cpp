// A slave node level with the master that no face accepts is either in the NTS blind spot between two
// faces (docs/theory.md §3.4: a finer master mesh helps, and the log says so) or beyond the master's
// boundary, outside its footprint (no face could take it: counted apart, not logged). Scenes: a cube's
// bottom four nodes above the ridge of a roof-shaped 2 × 2 plate, and beside a flat plate's edge.
#include <gtest/gtest.h>

#include "core/contact/penalty/penalty_term.hpp"
#include "core/mesh/generators.hpp"

namespace stoss::contact {
namespace {

struct Outcome {
  ContactReport report;
  std::vector<std::string> log;  ///< the lines about nodes no face accepts
};

/// One step of a faceted penalty pair cube/bottom on plate/top at rest, with the plate's nodes on x = 0
/// raised by `ridge` (a roof) and the cube's bottom at `cube_min`.
Outcome measure(double ridge, const Eigen::Vector3d& cube_min) {
  mesh::Mesh mesh;
  mesh.add_body("plate", mesh::box({-1, -1, -0.4}, {1, 1, 0}, {2, 2, 1}));
  mesh.add_body("cube", mesh::box(cube_min, cube_min + Eigen::Vector3d(0.1, 0.1, 0.1), {1, 1, 1}));
  Eigen::VectorXd x = mesh.reference_positions();
  for (int I = mesh.bodies[0].node_begin; I < mesh.bodies[0].node_end; ++I)
    if (std::abs(x[3 * I]) < 1e-12 && std::abs(x[3 * I + 2]) < 1e-12) x[3 * I + 2] = ridge;
  model::ContactPair pair;
  pair.slave = "cube/bottom";
  pair.master = "plate/top";
  pair.enforcement = model::Enforcement::penalty;
  pair.master_surface = model::MasterSurface::faceted;
  PenaltyContactTerm term(mesh, pair, 1e4);
  Outcome out;
  const time::LogFunction log = [&](const std::string& line) {  // the blind-spot lines only
    if (line.find("onto no face") != std::string::npos) out.log.push_back(line);
  };
  const Eigen::VectorXd v = Eigen::VectorXd::Zero(x.size());
  const time::StepContext step{x, v, 0.01, time::ForceRule::discrete_gradient(), &log};
  term.prepare_step(step);
  term.end_step(step, x);
  out.report = term.report();
  return out;
}

TEST(BlindSpot, NodesAboveAConvexRidgeAreTheBlindSpotAndLogged) {
  // Ridge z = 0.5 at x = 0, faces sloping 1 in 2; the nodes at x = ±0.05, 0.2 above the ridge, project
  // beyond the shared edge on both faces by more than ε_ext, with |g| ≈ 0.18 < ½ face.
  const Outcome o = measure(0.5, {-0.05, -0.05, 0.7});
  EXPECT_EQ(o.report.unassigned, 4);
  EXPECT_EQ(o.report.outside_footprint, 0);
  ASSERT_EQ(o.log.size(), 1u);
  EXPECT_NE(o.log[0].find("4 slave node(s)"), std::string::npos) << o.log[0];
  EXPECT_NE(o.log[0].find("refine the master mesh"), std::string::npos) << o.log[0];
}

TEST(BlindSpot, NodesBesideTheMastersEdgeAreOutsideItsFootprintAndNotLogged) {
  // A flat plate; the cube's bottom at x ∈ [1.1, 1.2], 0.01 above the plate's level: beyond its edge.
  const Outcome o = measure(0, {1.1, -0.05, 0.01});
  EXPECT_EQ(o.report.unassigned, 4);
  EXPECT_EQ(o.report.outside_footprint, 4);
  EXPECT_TRUE(o.log.empty()) << o.log.front();
}

}  // namespace
}  // namespace stoss::contact
