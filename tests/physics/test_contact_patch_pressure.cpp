// The contact patch test under a uniform pressure, solved as static load steps (issue 23 §6, issue 24 §3):
// two stacked blocks on rollers (the lower one's bottom holds z; xmin holds x and ymin holds y on both), so
// the exact pressure on the interface is uniform for any ν; a follower pressure ramp on the upper block's
// top; contact with the upper block's bottom as the slave. The system shall pass the load through the
// interface: the contact force equals the support's reaction and the pressure times the top's deformed area.
// Node-to-segment contact transmits it uniformly on matching meshes only (the scatter of non-matching ones is
// reported in docs/measurements.md, "Contact patch test under pressure"); mortar (docs/theory.md §4.7) on
// non-matching ones too (2×2 on 3×3, 3×3 on 2×2, 4×4 on 7×7), including a block whose mesh is turned 30°
// about z against the other's.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "../core/recording_observer.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"
#include "stacked_blocks.hpp"

namespace stoss {
namespace {

using nlohmann::json;

constexpr double applied_pressure = 10;

/// The static scene of the patch: `bodies` with `boundary`, the pressure ramp on upper/top, `pair`
/// (upper/bottom on lower/top plus the given fields).
json patch_scene(const json& bodies, const json& boundary, const json& pair_fields) {
  json pair = {{"slave", "upper/bottom"}, {"master", "lower/top"}, {"enforcement", "lagrange"}};
  pair.update(pair_fields);
  return {{"format", "stoss-scene/1"},
          {"bodies", bodies},
          {"boundary", boundary},
          {"loads",
           {{{"surface", "upper/top"}, {"pressure", applied_pressure}, {"amplitude", {{0, 0}, {1, 1}}}}}},
          {"contact", {pair}},
          {"time", {{"scheme", "static"}, {"step", 0.25}, {"end", 1}}}};
}

/// The stacked boxes on rollers; `pair_fields` e.g. {"master_surface": "smooth"} or {"discretization":
/// "mortar"}.
model::Model patch(int slave_divisions, int master_divisions, const json& pair_fields) {
  const json bodies = {testing::stacked_block("lower", 0, master_divisions, 2),
                       testing::stacked_block("upper", 0.5, slave_divisions, 2)};
  return scene::load(patch_scene(bodies, testing::roller_boundary(), pair_fields));
}

model::Model patch(int slave_divisions, int master_divisions, const char* master_surface) {
  return patch(slave_divisions, master_divisions, json{{"master_surface", master_surface}});
}

struct PatchResult {
  double contact_force, support_reaction, load, scatter;
  double pressure_error = 0;  ///< max |p_i − p| / p over the slave nodes, p the applied (Cauchy) pressure
  double contact_area = 0;    ///< the series contact_area at the end
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
  out.contact_area = r.series("contact_area").back();
  for (int node : m.mesh.surface_nodes("upper/bottom")) {
    const double p_i = r.frames.back().contact_pressure[node];
    out.scatter = std::max(out.scatter, std::abs(p_i - mean) / mean);
    out.pressure_error = std::max(out.pressure_error, std::abs(p_i - applied_pressure) / applied_pressure);
  }
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

/// Mortar's bounds (issue 24 §3): every slave node's −λ_j is the applied pressure p within 1e-8 (the exact
/// state is uniform, so the Cauchy pressure on the deformed interface is p itself), the contact force is the
/// load within 1e-10 and the support's reaction, and contact_area (Σ D_jj of the active nodes) the deformed
/// area.
void expect_mortar_patch_passed(const PatchResult& p, const std::string& label) {
  EXPECT_LT(p.pressure_error, 1e-8) << label;
  EXPECT_NEAR(p.contact_force, p.load, 1e-10 * p.load) << label;
  EXPECT_NEAR(p.contact_force, p.support_reaction, 1e-10 * p.load) << label;
  EXPECT_NEAR(p.contact_area * applied_pressure, p.load, 1e-8 * p.load) << label;
  std::printf("mortar patch %s: max |p_i − p|/p = %.3e, contact force / load − 1 = %.3e, area %.12f\n",
              label.c_str(), p.pressure_error, p.contact_force / p.load - 1, p.contact_area);
}

TEST(ContactPatchPressure, MortarTransmitsAUniformPressureAcrossNonMatchingMeshes) {
  for (const auto& [slave, master] : {std::pair{2, 3}, std::pair{3, 2}, std::pair{4, 7}}) {
    const model::Model m = patch(slave, master, json{{"discretization", "mortar"}});
    EXPECT_EQ(m.scene["contact"][0]["master_surface"], "faceted") << "mortar resolves to the faceted surface";
    expect_mortar_patch_passed(run_patch(m), std::to_string(slave) + "×" + std::to_string(slave) + " on " +
                                                 std::to_string(master) + "×" + std::to_string(master));
  }
}

/// The rhombi that tile the regular 12-gon with unit sides spanned by v_k at 30° (k − 1), k = 1 … 6, grown
/// one zone at a time: adding v_k moves the upper chain of the 12-gon of v_1 … v_{k−1} (from S = Σ v_i back
/// to 0) by v_k and fills the gap with the rhombi of v_k and each chain edge. Every face a parallelogram, so
/// the mortar integrals are exact on it (docs/theory.md (4.74)). Centred on the origin.
std::vector<std::array<Eigen::Vector2d, 4>> twelve_gon_rhombi() {
  const double pi = std::acos(-1.0);
  std::vector<Eigen::Vector2d> v;
  for (int k = 0; k < 6; ++k) v.emplace_back(std::cos(pi * k / 6), std::sin(pi * k / 6));
  std::vector<std::array<Eigen::Vector2d, 4>> out;
  Eigen::Vector2d sum = v[0];
  for (int k = 1; k < 6; ++k) {
    Eigen::Vector2d chain = sum;  // P_m = S − Σ_{i<m} v_i
    for (int m = 0; m < k; ++m) {
      out.push_back({chain - v[m], chain, chain + v[k], chain + v[k] - v[m]});
      chain -= v[m];
    }
    sum += v[k];
  }
  for (auto& rhombus : out)
    for (Eigen::Vector2d& corner : rhombus) corner -= 0.5 * sum;
  return out;
}

/// A block over the regular 12-gon of side `side`, its faces the rhombi of twelve_gon_rhombi each split into
/// `split` × `split`, the whole mesh turned by `turn` degrees about z, `layers` through z ∈ [z0, z0 + 0.5].
/// Surfaces bottom, top and side (outward).
json twelve_gon_block(const char* name, double z0, double side, int split, int layers, double turn) {
  const Eigen::Rotation2Dd rotation(std::acos(-1.0) * turn / 180);
  std::vector<Eigen::Vector2d> plane;
  const auto node = [&](const Eigen::Vector2d& x) {  // the index of a 2D node, merged by position
    for (size_t i = 0; i < plane.size(); ++i)
      if ((plane[i] - x).norm() < 1e-12) return static_cast<int>(i);
    plane.push_back(x);
    return static_cast<int>(plane.size()) - 1;
  };
  std::vector<std::array<int, 4>> quads;  // counter-clockwise seen from +z
  for (const auto& r : twelve_gon_rhombi()) {
    const Eigen::Vector2d a = side * r[0], e1 = side * (r[1] - r[0]) / split,
                          e2 = side * (r[3] - r[0]) / split;
    for (int i = 0; i < split; ++i)
      for (int j = 0; j < split; ++j) {
        const Eigen::Vector2d c = a + i * e1 + j * e2;
        std::array<int, 4> q{node(rotation * c), node(rotation * (c + e1)), node(rotation * (c + e1 + e2)),
                             node(rotation * (c + e2))};
        if (e1.x() * e2.y() - e1.y() * e2.x() < 0) std::swap(q[1], q[3]);
        quads.push_back(q);
      }
  }
  std::map<std::pair<int, int>, int> edge_count;  // the rim: edges of one quad only
  for (const auto& q : quads)
    for (int k = 0; k < 4; ++k) ++edge_count[std::minmax(q[k], q[(k + 1) % 4])];
  const int n = static_cast<int>(plane.size());
  json nodes = json::array(), hex8 = json::array(), bottom = json::array(), top = json::array(),
       sides = json::array();
  for (int k = 0; k <= layers; ++k)
    for (const Eigen::Vector2d& x : plane) nodes.push_back({x.x(), x.y(), z0 + 0.5 * k / layers});
  for (int k = 0; k < layers; ++k) {
    const int b = k * n, t = (k + 1) * n;
    for (const auto& q : quads) {
      hex8.push_back({b + q[0], b + q[1], b + q[2], b + q[3], t + q[0], t + q[1], t + q[2], t + q[3]});
      if (k == 0) bottom.push_back({q[0], q[3], q[2], q[1]});
      if (k == layers - 1) top.push_back({t + q[0], t + q[1], t + q[2], t + q[3]});
      for (int e = 0; e < 4; ++e)  // a counter-clockwise rim edge a → c has the outside on its right
        if (const int a = q[e], c = q[(e + 1) % 4]; edge_count[std::minmax(a, c)] == 1)
          sides.push_back({b + a, b + c, t + c, t + a});
    }
  }
  const json material = {{"youngs_modulus", 1000}, {"poisson_ratio", 0}, {"density", 1}};
  return {
      {"name", name},
      {"mesh",
       {{"nodes", nodes}, {"hex8", hex8}, {"surfaces", {{"bottom", bottom}, {"top", top}, {"side", sides}}}}},
      {"material", material}};
}

// A block turned 30° about z against the other cannot keep a box's outline: two squares turned 30° apart
// overlap only in part, the overhang carries no pressure and the exact state is no longer uniform. A regular
// 12-gon is its own image under the turn, so both blocks share the outline: the lower one tiled by 15 rhombi
// split 2 × 2, the upper one by the same 15 rhombi turned 30°. Rollers on a turned block's sides would have
// to hold the direction normal to each side, which `fix` (global x, y, z) cannot say; with ν = 0 the exact
// state has no lateral strain (S = E E_zz uniaxial, x and y stay put at any strain), so holding x and y on
// both blocks' sides and z at the lower bottom keeps it exact: σ_zz = −p uniform in both blocks.
TEST(ContactPatchPressure, MortarTransmitsAUniformPressureUnderAMeshTurned30Degrees) {
  const double side = 0.3;
  const json bodies = {twelve_gon_block("lower", 0, side, 2, 2, 0),
                       twelve_gon_block("upper", 0.5, side, 1, 2, 30)};
  const json boundary = {{{"surface", "lower/bottom"}, {"fix", "z"}},
                         {{"surface", "lower/side"}, {"fix", "xy"}},
                         {{"surface", "upper/side"}, {"fix", "xy"}}};
  const PatchResult p = run_patch(scene::load(patch_scene(bodies, boundary, {{"discretization", "mortar"}})));
  expect_mortar_patch_passed(p, "12-gon turned 30°");
  const double area = 3 * (2 + std::sqrt(3.0)) * side * side;  // the regular 12-gon of side a: 3 (2 + √3) a²
  EXPECT_NEAR(p.load, applied_pressure * area, 1e-12) << "ν = 0: the top keeps its area";
}

}  // namespace
}  // namespace stoss
