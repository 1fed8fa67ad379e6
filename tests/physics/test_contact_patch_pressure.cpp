// The contact patch test under a uniform pressure, solved as static load steps (issue 23 §6): two stacked
// blocks on rollers (the lower one's bottom holds z; xmin holds x and ymin holds y on both), so the exact
// pressure on the interface is uniform for any ν; a follower pressure ramp on the upper block's top; NTS
// contact with the upper block's bottom as the slave. The system shall pass the load through the interface:
// the contact force equals the support's reaction and the pressure times the top's deformed area. Matching
// meshes transmit it uniformly; the scatter of non-matching ones is reported (its bound belongs to the
// mortar issue, 24 §3) in docs/measurements.md, "Contact patch test under pressure".
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "../core/recording_observer.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"
#include "stacked_blocks.hpp"

namespace stoss {
namespace {

using nlohmann::json;

constexpr double applied_pressure = 10;

model::Model patch(int slave_divisions, int master_divisions, const std::string& master_surface) {
  return scene::load(
      json{{"format", "stoss-scene/1"},
           {"bodies",
            {testing::stacked_block("lower", 0, master_divisions, 2),
             testing::stacked_block("upper", 0.5, slave_divisions, 2)}},
           {"boundary", testing::roller_boundary()},
           {"loads",
            {{{"surface", "upper/top"}, {"pressure", applied_pressure}, {"amplitude", {{0, 0}, {1, 1}}}}}},
           {"contact",
            {{{"slave", "upper/bottom"},
              {"master", "lower/top"},
              {"enforcement", "lagrange"},
              {"master_surface", master_surface}}}},
           {"time", {{"scheme", "static"}, {"step", 0.25}, {"end", 1}}}});
}

struct PatchResult {
  double contact_force, support_reaction, load, scatter;
};

/// The last step's contact force (z), the lower support's reaction (z), p times the deformed top's area
/// projected on z (the pressure's resultant: the rollers take no z force from the upper block),
/// and max |p_i − p̄| / p̄ over the slave nodes, p̄ the contact force over the slave's reference area.
PatchResult run_patch(const model::Model& m) {
  testing::RecordingObserver r;
  const model::Summary s = simulate(m, r);
  EXPECT_TRUE(s.completed);
  const Eigen::VectorXd& x = r.frames.back().position;
  double area = 0;
  for (const mesh::Quad& q : m.mesh.surface("upper/top")) {
    const auto at = [&](int k) { return Eigen::Vector3d(x.segment<3>(3 * q[k])); };
    area += 0.5 * (at(2) - at(0)).cross(at(3) - at(1)).z();  // ∫ n_z da of the bilinear face
  }
  PatchResult out{r.series("contact_force", 2).back(), r.series("reaction_force", 2).back(),
                  applied_pressure * area, 0};
  const double mean = out.contact_force / 1.0;  // the slave's reference area is 1
  for (int node : m.mesh.surface_nodes("upper/bottom"))
    out.scatter = std::max(out.scatter, std::abs(r.frames.back().contact_pressure[node] - mean) / mean);
  return out;
}

TEST(ContactPatchPressure, MatchingMeshesTransmitTheLoadUniformly) {
  const PatchResult p = run_patch(patch(3, 3, "faceted"));
  EXPECT_NEAR(p.contact_force, p.support_reaction, 1e-10 * p.load);
  EXPECT_NEAR(p.contact_force, p.load, 1e-8 * p.load)
      << "the follower pressure's resultant on the deformed top";
  EXPECT_GT(p.load, applied_pressure * 1.001) << "the top widens under load (ν = 0.3 on rollers)";
  EXPECT_LT(p.scatter, 1e-8);
}

TEST(ContactPatchPressure, NonMatchingMeshesPassTheWholeLoadThroughTheInterface) {
  for (const auto& [slave, master] : {std::pair{3, 2}, std::pair{2, 3}})
    for (const char* surface : {"faceted", "smooth"}) {
      const PatchResult p = run_patch(patch(slave, master, surface));
      EXPECT_NEAR(p.contact_force, p.support_reaction, 1e-10 * p.load)
          << slave << " on " << master << surface;
      EXPECT_NEAR(p.contact_force, p.load, 1e-8 * p.load) << slave << " on " << master << " " << surface;
      std::printf("patch %d×%d on %d×%d, %s: max |p_i − p̄|/p̄ = %.3e, contact force %.9f, load %.9f\n", slave,
                  slave, master, master, surface, p.scatter, p.contact_force, p.load);
    }
}

}  // namespace
}  // namespace stoss
