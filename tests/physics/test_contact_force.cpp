// The system shall record the force each contact pair's master exerts on its slave and the pair's contact
// area (issue 23 §4; docs/results.md series/contact_force, contact_area; docs/theory.md (5b.12)):
// - a block pressed onto a block by a uniform load on rollers, brought to rest, carries the load through the
//   pair: contact_force = p A e_z within 1e-8 of the load, the upper block's forces (contact, load, its
//   rollers' reaction_force) sum to 0 within 1e-8, and contact_area is the full patch, 1, within 1e-12;
// - two bars colliding end-on, free: Σ_n h_n contact_force_n equals the momentum the slave bar gains, and
//   minus the master bar's, within 1e-10 of it (Newton's third law and the impulse of the step's discrete
//   force), also when located impacts split steps into sub-steps;
// - with the master bar's far end held, the support's Σ_n h_n reaction_force_n closes the master bar's
//   momentum balance within the same bound, with and without sub-steps.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "../core/recording_observer.hpp"
#include "core/run/problem.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"
#include "stacked_blocks.hpp"

namespace stoss {
namespace {

using nlohmann::json;

constexpr double pressure = 5;  // on the upper block's top, area 1 × 1

/// The patch test's setting (issue 23 §6) brought to rest: a 2 × 2 × 1 block on a 3 × 3 × 1 block, both on
/// rollers (lower bottom fix z, xmin fix x and ymin fix y on both), a uniform load p on the upper top. The
/// load is a dead traction (0, 0, −p) per reference area, so that it totals p A however the top deforms (a
/// follower pressure totals p times the deformed area: 5.0185 here, the top widened by ν p / E on each
/// side). HHT-α with α = −1/3 and a step far above the slowest period damps every mode
/// (test_contact_patch.cpp). Boundary entries: 0 lower/bottom, 1 lower/xmin, 2 lower/ymin, 3 upper/xmin,
/// 4 upper/ymin.
model::Model pressed_blocks() {
  return scene::load(
      json{{"format", "stoss-scene/1"},
           {"bodies", {testing::stacked_block("lower", 0, 3, 1), testing::stacked_block("upper", 0.5, 2, 1)}},
           {"contact", json::array({{{"slave", "upper/bottom"}, {"master", "lower/top"}}})},
           {"boundary", testing::roller_boundary()},
           {"loads", json::array({{{"surface", "upper/top"}, {"traction", {0, 0, -pressure}}}})},
           {"time", {{"scheme", "hht"}, {"alpha", -1.0 / 3}, {"step", 0.04}, {"end", 16.0}}},
           {"solver", {{"tolerance", 1e-12}}},
           {"output", {{"every", 100}}}});
}

TEST(ContactForce, ABlockPressedOntoABlockPassesTheLoadThroughThePairOverTheWholePatch) {
  const model::Model m = pressed_blocks();
  testing::RecordingObserver r;
  ASSERT_TRUE(simulate(m, r).completed);
  ASSERT_TRUE(r.has_series("contact_force"));
  ASSERT_TRUE(r.has_series("contact_area"));
  const double load = pressure * 1.0;
  const double fx = r.series("contact_force", 0).back(), fy = r.series("contact_force", 1).back(),
               fz = r.series("contact_force", 2).back();
  EXPECT_EQ(r.series("contact_force", 2).front(), 0) << "row 0 is 0";
  EXPECT_NEAR(fz, load, 1e-8 * load) << "the lower block pushes the upper one up with the load";
  // At rest the upper block's forces balance: contact, load (0, 0, −p A) and its rollers' reactions.
  const auto reaction = [&](int entry, int c) { return r.series("reaction_force", 3 * entry + c).back(); };
  EXPECT_NEAR(fx + reaction(3, 0) + reaction(4, 0), 0, 1e-8 * load);
  EXPECT_NEAR(fy + reaction(3, 1) + reaction(4, 1), 0, 1e-8 * load);
  EXPECT_NEAR(fz + reaction(3, 2) + reaction(4, 2) - load, 0, 1e-8 * load);
  const double area = r.series("contact_area").back();
  EXPECT_NEAR(area, 1.0, 1e-12) << "every slave node in contact: Σ A_I is the interface's area";
  std::printf(
      "pressed blocks: contact force (%.2e, %.2e, %.12f) for a load %.1f, upper rollers (%.2e, %.2e), "
      "contact area %.15f\n",
      fx, fy, fz, load, reaction(3, 0) + reaction(4, 0), reaction(3, 1) + reaction(4, 1), area);
}

/// Σ over body `b`'s nodes of (M v)_z.
double body_momentum_z(const model::Model& m, const solve::SparseMatrix& M, const Eigen::VectorXd& v, int b) {
  const Eigen::VectorXd p = M * v;
  double out = 0;
  for (int I = m.mesh.bodies[b].node_begin; I < m.mesh.bodies[b].node_end; ++I) out += p[3 * I + 2];
  return out;
}

struct ImpulseBalance {
  double impulse = 0;           ///< Σ_n h_n contact_force_n,z
  double slave_gain = 0;        ///< Δp_z of the slave bar (left) from the first frame to the last
  double master_gain = 0;       ///< Δp_z of the master bar (right)
  double lateral = 0;           ///< largest |contact_force_x|, |contact_force_y|
  double largest_force = 0;     ///< largest |contact_force_z|
  double largest_area = 0;      ///< largest contact_area: the bars' 0.1 × 0.1 end
  double reaction_impulse = 0;  ///< Σ_n h_n reaction_force_n,z (with the master's far end held)
};

/// The colliding bars with `impact`; `held`: the master bar's far end (right/top) held.
ImpulseBalance colliding_bars(const std::string& impact, bool held = false) {
  json scene =
      json::parse(std::ifstream(std::string(STOSS_SOURCE_DIR) + "/api/examples/colliding_bars.json"));
  scene["contact"][0]["impact"] = impact;
  if (held) scene["boundary"] = json::array({{{"surface", "right/top"}}});
  scene["solver"]["tolerance"] = 1e-12;
  const model::Model m = scene::load(scene);
  testing::RecordingObserver r;
  EXPECT_TRUE(simulate(m, r).completed) << impact;
  const solve::SparseMatrix M = run::build_problem(m).mass;  // massless contact surfaces with `located`
  ImpulseBalance out;
  const auto h = r.series("step_size"), fz = r.series("contact_force", 2), area = r.series("contact_area");
  for (size_t n = 1; n < fz.size(); ++n) {
    out.impulse += h[n] * fz[n];
    out.largest_area = std::max(out.largest_area, area[n]);
    out.largest_force = std::max(out.largest_force, std::abs(fz[n]));
    if (held) out.reaction_impulse += h[n] * r.series("reaction_force", 2)[n];
    for (int c : {0, 1}) out.lateral = std::max(out.lateral, std::abs(r.series("contact_force", c)[n]));
  }
  const Eigen::VectorXd &v0 = r.frames.front().velocity, &v1 = r.frames.back().velocity;
  out.slave_gain = body_momentum_z(m, M, v1, 0) - body_momentum_z(m, M, v0, 0);
  out.master_gain = body_momentum_z(m, M, v1, 1) - body_momentum_z(m, M, v0, 1);
  std::printf(
      "colliding bars (%s%s): Σ h F_z = %.15e, slave Δp_z = %.15e, master Δp_z = %.15e, Σ h r_z = %.15e, "
      "largest contact area %.6f\n",
      impact.c_str(), held ? ", far end held" : "", out.impulse, out.slave_gain, out.master_gain,
      out.reaction_impulse, out.largest_area);
  return out;
}

void expect_impulse_is_momentum_gain(const ImpulseBalance& b) {
  ASSERT_LT(b.slave_gain, 0) << "the master pushes the slave back";
  EXPECT_NEAR(b.impulse, b.slave_gain, 1e-10 * std::abs(b.slave_gain));
  EXPECT_NEAR(b.impulse, -b.master_gain + b.reaction_impulse, 1e-10 * std::abs(b.slave_gain))
      << "Newton's third law: the master gains −Σ h f_c, and its support's impulse";
  EXPECT_LT(b.lateral, 1e-10 * b.largest_force) << "an end-on impact pushes along the bars";
}

TEST(ContactForce, TheImpulseOfTheContactForceIsTheMomentumTheSlaveBarGains) {
  const ImpulseBalance b = colliding_bars("persist");
  expect_impulse_is_momentum_gain(b);
  EXPECT_NEAR(b.largest_area, 0.01, 1e-14) << "the bar's whole end is in contact";
}

// A located impact ends a sub-step at each activation and release (docs/theory.md §4.6.2): the step's row
// is Σ h_k f_k / h over its sub-steps, or the impulse would miss the sub-steps before the last.
TEST(ContactForce, StepsSplitAtLocatedImpactsWeightTheirSubstepsForcesByTheirH) {
  expect_impulse_is_momentum_gain(colliding_bars("located"));
}

// The supports' reaction_force follows the same rule (docs/theory.md (5b.10)): with the master bar's far end
// held, its impulse Σ_n h_n r_n is what the master bar gains beyond −Σ h f_c, and with located impacts the
// sub-steps of the reaction are weighted too.
TEST(ContactForce, TheReactionsImpulseClosesTheHeldMasterBarsMomentumAlsoInSubsteps) {
  for (const char* impact : {"persist", "located"}) {
    const ImpulseBalance b = colliding_bars(impact, true);
    EXPECT_GT(std::abs(b.reaction_impulse), 0.01 * std::abs(b.impulse))
        << impact << ": the wave reaches the end";
    expect_impulse_is_momentum_gain(b);
  }
}

}  // namespace
}  // namespace stoss
