// Hertz indentation as static load steps (issue 23 §6; docs/measurements.md, "Hertz indentation"): the
// example api/examples/hertz_indentation.json, a quarter model on the coarsest of the three Gmsh meshes
// (element edge h0 = 0.05 at the contact). A sphere of radius R = 1 (its lower cap, E_s = 1000 E) is driven
// 2 % of R into a block (E = 1, ν = 0.3) in eight load steps; NTS Lagrange contact, slave block/top, master
// sphere/cap. At each level from δ/R = 0.5 % to 2 % (every 0.25 %):
// - the force F = 4 |contact_force_z| and the sphere's support reaction agree within 1e-5 F (the Newton
//   tolerance is relative to the stiff sphere's forces; measured: at most 2.0e-6 F);
// - faceted master: F within 5 % of Hertz's (4/3) E* √R δ^(3/2) (measured on this mesh: at most 3.7 %, at
//   0.75 %, where a spans 1.7 elements; the finer meshes are the benchmark's);
// - smooth master: F is below Hertz's (the spline lies inside the sphere's nodes, ℓ²/(3R) above the pole, ℓ
//   the cap's face size) and within 5 % of Hertz's at that shortened indentation δ − ℓ²/(3R) (measured: at
//   most 3.3 %; against δ itself it is 6–25 % low on this mesh, and the offset falls as ℓ² on finer ones);
// - both: the contact radius √(4 contact_area / π) within one element edge ℓ of √(Rδ) (measured: at most
//   0.59 ℓ).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../core/recording_observer.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"

namespace stoss {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path examples = fs::path(STOSS_SOURCE_DIR) / "api/examples";
constexpr double R = 1, depth = 0.02;  // the sphere's radius and the prescribed motion's size in the example

/// Hertz's effective modulus with both bodies' compliance, 1/E* = (1 − ν²)/E + (1 − ν_s²)/E_s
/// (docs/measurements.md, "Hertz indentation", (H1)), from the scene's materials.
double effective_modulus(const json& scene) {
  double compliance = 0;
  for (const json& body : scene["bodies"]) {
    const double E = body["material"]["youngs_modulus"], nu = body["material"]["poisson_ratio"];
    compliance += (1 - nu * nu) / E;
  }
  return 1 / compliance;
}

/// The longest edge of the cap's faces that touch the pole (the sphere's lowest node): the face size ℓ.
double pole_face_size(const model::Model& m) {
  const std::vector<Eigen::Vector3d>& X = m.mesh.nodes;
  const std::vector<int> nodes = m.mesh.surface_nodes("sphere/cap");
  const int pole =
      *std::min_element(nodes.begin(), nodes.end(), [&](int a, int b) { return X[a].norm() < X[b].norm(); });
  double size = 0;
  for (const mesh::Quad& q : m.mesh.surface("sphere/cap"))
    if (std::find(q.begin(), q.end(), pole) != q.end())
      for (int k = 0; k < 4; ++k) size = std::max(size, (X[q[k]] - X[q[(k + 1) % 4]]).norm());
  return size;
}

struct Level {
  double delta, force, reaction, radius;
};

/// The example's run on the coarse mesh with `master_surface`: the levels from δ/R = 0.5 %, the pole's face
/// size ℓ and E* (H1).
struct HertzRun {
  std::vector<Level> levels;
  double face_size = 0, E_star = 0;
  double peak_pressure = 0;  ///< the largest nodal contact_pressure of the last frame (δ/R = 2 %)
};

/// `discretization`: the pair's contact.discretization ("mortar" integrates on the faceted surface).
HertzRun run(const std::string& master_surface, const std::string& discretization = "node_to_segment") {
  json scene = json::parse(std::ifstream(examples / "hertz_indentation.json"));
  scene["contact"][0]["master_surface"] = master_surface;
  scene["contact"][0]["discretization"] = discretization;
  const model::Model m = scene::load(scene, examples);
  HertzRun out{{}, pole_face_size(m), effective_modulus(scene)};
  testing::RecordingObserver r;
  const model::Summary s = simulate(m, r);
  EXPECT_TRUE(s.completed);
  EXPECT_EQ(s.verdict, "ok");
  const auto fz = r.series("contact_force", 2), area = r.series("contact_area"),
             reaction = r.series("reaction_force", 2);  // entry 0: sphere/top, holding the sphere down
  for (size_t n = 1; n < r.rows.size(); ++n)            // the quarter model's force and area, times 4
    if (depth * r.rows[n].time >= 0.005 * R - 1e-12)    // Hertz's range here: δ/R from 0.5 to 2 %
      out.levels.push_back(
          {depth * r.rows[n].time, -4 * fz[n], -4 * reaction[n], std::sqrt(4 * area[n] / M_PI)});
  EXPECT_EQ(out.levels.size(), 7u) << "0.5 % to 2 % in steps of 0.25 %";
  EXPECT_NEAR(r.frames.back().time, 1, 1e-12);
  out.peak_pressure = r.frames.back().contact_pressure.maxCoeff();
  return out;
}

double hertz_force(double E_star, double delta) {  // (H2)
  return 4.0 / 3.0 * E_star * std::sqrt(R) * std::pow(delta, 1.5);
}

/// At every level: the sphere's support carries the contact force, F within 5 % of (H2) and a within one edge
/// of (H3); prints the rows as `label`.
void expect_hertz_levels(const HertzRun& hertz, const char* label) {
  const double size = hertz.face_size;
  for (const Level& l : hertz.levels) {
    const double F = hertz_force(hertz.E_star, l.delta), a = std::sqrt(R * l.delta);  // (H2), (H3)
    EXPECT_NEAR(l.reaction, l.force, 1e-5 * l.force) << "the sphere's support carries the contact force";
    EXPECT_NEAR(l.force / F, 1, 0.05) << "δ/R = " << l.delta / R;
    EXPECT_NEAR(l.radius, a, size) << "δ/R = " << l.delta / R;
    std::printf("hertz %s δ/R = %.4f: F %.6e, Hertz %.6e (%+.2f %%), a %.4f, √(Rδ) %.4f (%+.2f ℓ)\n", label,
                l.delta / R, l.force, F, 100 * (l.force / F - 1), l.radius, a, (l.radius - a) / size);
  }
}

TEST(HertzIndentation, FacetedMasterMatchesHertzForceAndContactRadius) {
  const HertzRun hertz = run("faceted");
  EXPECT_NEAR(hertz.face_size, 0.05, 1e-3) << "the coarse mesh's h0 (hertz_indentation.geo)";
  expect_hertz_levels(hertz, "faceted");
}

TEST(HertzIndentation, SmoothMasterMatchesHertzAtTheIndentationOfItsSurface) {
  const HertzRun hertz = run("smooth");
  const double size = hertz.face_size, E_star = hertz.E_star;
  const double offset = size * size / (3 * R);  // (H4): how far the spline lies above the pole's node
  for (const Level& l : hertz.levels) {
    const double F = hertz_force(E_star, l.delta), a = std::sqrt(R * l.delta);
    const double F_surface = hertz_force(E_star, l.delta - offset);
    EXPECT_NEAR(l.reaction, l.force, 1e-5 * l.force);
    EXPECT_LT(l.force, F) << "δ/R = " << l.delta / R << ": the spline's sphere is smaller by " << offset;
    EXPECT_NEAR(l.force / F_surface, 1, 0.05) << "δ/R = " << l.delta / R;
    EXPECT_NEAR(l.radius, a, size) << "δ/R = " << l.delta / R;
    std::printf(
        "hertz smooth δ/R = %.4f: F %.6e, Hertz %.6e (%+.2f %%), at δ − ℓ²/(3R) %.6e (%+.2f %%), a %.4f, "
        "√(Rδ) %.4f (%+.2f ℓ)\n",
        l.delta / R, l.force, F, 100 * (l.force / F - 1), F_surface, 100 * (l.force / F_surface - 1),
        l.radius, a, (l.radius - a) / size);
  }
}

// Mortar (issue 24 §4; docs/theory.md §4.7): the same example with "discretization": "mortar", on the coarse
// mesh (the medium and fine ones are the benchmark's, docs/measurements.md): F within 5 % of Hertz's at every
// level, as node-to-segment's above (measured: at most 3.28 %, at 0.75 %, where a spans 1.7 elements;
// node-to-segment there: 3.68 %), the reaction as above, a within one edge (measured 0.57), and the peak
// nodal pressure −λ_j at 2 % within 5 % of Hertz's p₀ = 2 E* a / (π R) (H3) (measured +3.23 %).
TEST(HertzIndentation, MortarMatchesHertzForcePeakPressureAndContactRadius) {
  const HertzRun hertz = run("faceted", "mortar");
  expect_hertz_levels(hertz, "mortar");
  const double p0 = 2 * hertz.E_star * std::sqrt(R * depth) / (M_PI * R);
  EXPECT_NEAR(hertz.peak_pressure / p0, 1, 0.05);
  std::printf("hertz mortar peak pressure at δ/R = %.3f: %.6e, Hertz p₀ %.6e (%+.2f %%)\n", depth / R,
              hertz.peak_pressure, p0, 100 * (hertz.peak_pressure / p0 - 1));
}

// One static load step to δ/R = 2 %: the undeformed block lets the sphere reach nodes outside the true
// contact in the first pass, and the step must be able to release them again (docs/theory.md §3.5). Refused
// their release, 2 nodes stayed attached in tension and F was 7.2 % below Hertz; now +0.94 %, with the
// 8 steps' +0.1 % (the bound 3 % is the goal).
TEST(HertzIndentation, OneLargeStaticStepReleasesTheNodesItsFirstPassReached) {
  json scene = json::parse(std::ifstream(examples / "hertz_indentation.json"));
  scene["time"]["step"] = 1.0;
  testing::RecordingObserver r;
  r.allow_suspect();  // one step this large takes 25 Newton iterations, more than (V6) expects of a step
  ASSERT_TRUE(simulate(scene::load(scene, examples), r).completed);
  for (const model::Check& c : r.summary.checks)
    EXPECT_TRUE(c.passed || c.name == "newton_iterations_per_step");
  for (const std::string& line : r.logs)
    EXPECT_EQ(line.find("kept active with tensile"), std::string::npos) << line;
  const double F = -4 * r.series("contact_force", 2).back(),
               hertz = hertz_force(effective_modulus(scene), depth);
  EXPECT_NEAR(F / hertz, 1, 0.03);
  std::printf("hertz faceted, one step to δ/R = %.3f: F %.6e, Hertz %.6e (%+.2f %%)\n", depth / R, F, hertz,
              100 * (F / hertz - 1));
}

}  // namespace
}  // namespace stoss
