// The model's own logic: scheme names, the step count, scheme/contact conflicts, effects and the series
// layout.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "core/model/model.hpp"
#include "core/model/observer.hpp"

namespace stoss::model {
namespace {

// --- Scheme names ----------------------------------------------------------------------------------

TEST(Scheme, EveryNameRoundTrips) {
  std::set<std::string> names;
  for (Scheme s : all_schemes) {
    const std::string name = to_string(s);
    EXPECT_NE(name, "unknown");
    names.insert(name);
    const std::optional<Scheme> parsed = scheme_from_string(name);
    ASSERT_TRUE(parsed.has_value()) << name;
    EXPECT_EQ(*parsed, s) << name;
  }
  EXPECT_EQ(names.size(), std::size(all_schemes)) << "two schemes share a name";
}

TEST(Scheme, TheDocumentedNamesAreTheNames) {
  EXPECT_EQ(scheme_from_string("energy_momentum"), Scheme::energy_momentum);
  EXPECT_EQ(scheme_from_string("midpoint"), Scheme::midpoint);
  EXPECT_EQ(scheme_from_string("hht"), Scheme::hht);
  EXPECT_EQ(scheme_from_string("generalized_alpha"), Scheme::generalized_alpha);
  EXPECT_EQ(std::size(all_schemes), 4u) << "a new scheme: add its name here and to docs/scene.md";
}

TEST(Scheme, UnknownNamesAreNullopt) {
  for (const char* name : {"", "HHT", "Midpoint", "energy-momentum", "energy_momentum ", "newmark", "unknown",
                           "generalized_alpha\n", "alpha"})
    EXPECT_EQ(scheme_from_string(name), std::nullopt) << "'" << name << "'";
}

// --- Step count ------------------------------------------------------------------------------------

int steps(double end, double step) {
  TimeSpec t;
  t.end = end;
  t.step = step;
  return t.steps();
}

TEST(TimeSpec, AnEndWithinRoundOffOfAMultipleOfTheStepGivesThatMultiple) {
  EXPECT_EQ(steps(1, 0.01), 100);
  EXPECT_EQ(steps(0.9, 0.03), 30);    // 0.9 / 0.03 = 30.000000000000004 in doubles: not 31
  EXPECT_EQ(steps(1.1, 0.011), 100);  // 100.00000000000001
  EXPECT_EQ(steps(0.3, 0.1), 3);      // 0.3 / 0.1 = 2.9999999999999996
  EXPECT_EQ(steps(0.7, 0.1), 7);      // 0.7 / 0.1 = 6.999999999999999
  EXPECT_EQ(steps(2.0, 0.05), 40);
  EXPECT_EQ(steps(0.5, 0.5), 1);
  EXPECT_EQ(steps(3, 1), 3);
}

TEST(TimeSpec, APartialLastStepCountsAsAStep) {
  EXPECT_EQ(steps(0.105, 0.01), 11);
  EXPECT_EQ(steps(1.001, 0.01), 101);
  EXPECT_EQ(steps(0.01, 1), 1) << "an end before the first step still takes one";
}

TEST(TimeSpec, NonPositiveEndOrStepGivesNoSteps) {
  EXPECT_EQ(steps(0, 0.01), 0);
  EXPECT_EQ(steps(-1, 0.01), 0);
  EXPECT_EQ(steps(1, 0), 0);
  EXPECT_EQ(steps(1, -0.01), 0);
  EXPECT_EQ(TimeSpec{}.steps(), 0) << "the defaults (step 0, end 0)";
}

// The limits' counts (issue 22 §2, §3): with a tolerance end/min_step steps; with frames at an interval and
// fixed steps one clipped step per frame on top; frames end/interval + 1 (the end as the last).
TEST(TimeSpec, TheStepBoundUsesMinStepWithAToleranceAndTheFramesTheInterval) {
  EXPECT_EQ(step_bound(1, 0.01, 1e-4, std::nullopt), 10000);
  EXPECT_EQ(step_bound(1, 0.01, std::nullopt, std::nullopt), 100);
  EXPECT_EQ(step_bound(1, 0.01, std::nullopt, 0.1), 110);
  EXPECT_EQ(step_bound(1, 0.01, 1e-3, 0.1), 1010) << "a landing step may be shorter than min_step";
  OutputSpec o;
  o.interval = 0.1;
  EXPECT_EQ(o.frame_count(12345, 1.0), 11);
  EXPECT_EQ(o.frame_count(12345, 1.05), 12) << "k·interval for k = 0…10 and the end";
  o.interval.reset();
  o.every = 5;
  EXPECT_EQ(o.frame_count(12, 1.0), 4) << "without an interval: by every, as before";
}

// --- Scheme / contact conflicts --------------------------------------------------------------------

/// The rules of contact_scheme_conflict's doc comment, written out independently: which field is at fault.
std::optional<std::string> expected_conflict_field(Scheme scheme, Enforcement enforcement,
                                                   ImpactMode impact) {
  if (impact == ImpactMode::velocity_correction && scheme != Scheme::energy_momentum) return "impact";
  if (enforcement == Enforcement::penalty && (scheme == Scheme::hht || scheme == Scheme::generalized_alpha))
    return "enforcement";
  return std::nullopt;
}

std::string describe(Scheme scheme, Enforcement enforcement, ImpactMode impact) {
  const char* enforcement_names[] = {"lagrange", "penalty"};
  const char* impact_names[] = {"persist", "exact", "velocity_correction"};
  return to_string(scheme) + " × " + enforcement_names[static_cast<int>(enforcement)] + " × " +
         impact_names[static_cast<int>(impact)];
}

TEST(ContactSchemeConflict, EveryCombinationFollowsTheDocumentedRules) {
  int conflicts = 0, combinations = 0;
  for (Scheme scheme : all_schemes)
    for (Enforcement enforcement : {Enforcement::lagrange, Enforcement::penalty})
      for (ImpactMode impact : {ImpactMode::persist, ImpactMode::exact, ImpactMode::velocity_correction}) {
        SCOPED_TRACE(describe(scheme, enforcement, impact));
        ++combinations;
        const std::optional<SchemeConflict> conflict = contact_scheme_conflict(scheme, enforcement, impact);
        const std::optional<std::string> field = expected_conflict_field(scheme, enforcement, impact);
        ASSERT_EQ(conflict.has_value(), field.has_value());
        if (!conflict) continue;
        ++conflicts;
        EXPECT_EQ(conflict->field, *field);
        const std::string quoted_scheme = std::string("\"").append(to_string(scheme)).append("\"");
        EXPECT_NE(conflict->reason.find(quoted_scheme), std::string::npos)
            << "the reason names the scheme: " << conflict->reason;
      }
  EXPECT_EQ(combinations, 24);
  // velocity_correction: 3 schemes × 2 enforcements; penalty with hht/generalized_alpha and another
  // impact: 2 schemes × 2 impacts.
  EXPECT_EQ(conflicts, 10);
}

TEST(ContactSchemeConflict, VelocityCorrectionNeedsEnergyMomentum) {
  for (Scheme scheme : {Scheme::midpoint, Scheme::hht, Scheme::generalized_alpha}) {
    const auto conflict =
        contact_scheme_conflict(scheme, Enforcement::lagrange, ImpactMode::velocity_correction);
    ASSERT_TRUE(conflict.has_value()) << to_string(scheme);
    EXPECT_EQ(conflict->field, "impact");
    EXPECT_EQ(conflict->reason, "\"velocity_correction\" needs time.scheme \"energy_momentum\", got \"" +
                                    to_string(scheme) + "\"");
  }
  EXPECT_FALSE(contact_scheme_conflict(Scheme::energy_momentum, Enforcement::lagrange,
                                       ImpactMode::velocity_correction));
  EXPECT_FALSE(contact_scheme_conflict(Scheme::energy_momentum, Enforcement::penalty,
                                       ImpactMode::velocity_correction));
}

TEST(ContactSchemeConflict, PenaltyHasNoAlphaWeightedForm) {
  for (Scheme scheme : {Scheme::hht, Scheme::generalized_alpha}) {
    const auto conflict = contact_scheme_conflict(scheme, Enforcement::penalty, ImpactMode::persist);
    ASSERT_TRUE(conflict.has_value()) << to_string(scheme);
    EXPECT_EQ(conflict->field, "enforcement");
    EXPECT_EQ(conflict->reason, "\"penalty\" is not implemented with time.scheme \"" + to_string(scheme) +
                                    "\"; use energy_momentum or midpoint");
  }
  for (Scheme scheme : {Scheme::energy_momentum, Scheme::midpoint})
    EXPECT_FALSE(contact_scheme_conflict(scheme, Enforcement::penalty, ImpactMode::persist))
        << to_string(scheme);
}

TEST(ContactSchemeConflict, BothRulesBrokenNamesTheImpactFirst) {
  const auto conflict =
      contact_scheme_conflict(Scheme::hht, Enforcement::penalty, ImpactMode::velocity_correction);
  ASSERT_TRUE(conflict.has_value());
  EXPECT_EQ(conflict->field, "impact");
}

// --- Effects ---------------------------------------------------------------------------------------

ContactPair pair(const std::string& slave, const std::string& master, double friction) {
  ContactPair c;
  c.slave = slave;
  c.master = master;
  c.friction = friction;
  return c;
}

TEST(Model, HasEffectMatchesWholeEntriesOnly) {
  Model m;
  m.effects = {effect::inertia, "contact_frictional:a/top,b/bottom"};
  EXPECT_TRUE(m.has_effect("inertia"));
  EXPECT_TRUE(m.has_effect("contact_frictional:a/top,b/bottom"));
  EXPECT_FALSE(m.has_effect("contact_frictional")) << "a prefix of an entry is not the effect";
  EXPECT_FALSE(m.has_effect("inert"));
  EXPECT_FALSE(m.has_effect(""));
  EXPECT_FALSE(Model{}.has_effect(effect::inertia));
}

TEST(Model, DofCountIsThreePerNode) {
  Model m;
  EXPECT_EQ(m.dof_count(), 0);
  m.mesh.nodes.assign(5, Eigen::Vector3d::Zero());
  EXPECT_EQ(m.dof_count(), 15);
}

TEST(ResolveEffects, ABareModelHasInertiaAndElasticity) {
  EXPECT_EQ(resolve_effects(Model{}), (std::vector<std::string>{"inertia", "elasticity"}));
}

TEST(ResolveEffects, ZeroGravityIsNoGravity) {
  Model m;
  m.gravity = Eigen::Vector3d::Zero();
  EXPECT_EQ(resolve_effects(m), (std::vector<std::string>{"inertia", "elasticity"}));
  m.gravity = Eigen::Vector3d(0, 0, -9.81);
  EXPECT_EQ(resolve_effects(m), (std::vector<std::string>{"inertia", "elasticity", "gravity"}));
}

TEST(ResolveEffects, EverythingInTheDocumentedOrder) {
  Model m;
  m.gravity = Eigen::Vector3d(0, -1, 0);
  m.boundary.push_back(Boundary{"plate/bottom", {true, true, true}});
  m.contact = {pair("ball/surface", "plate/top", 0.3), pair("a/s", "b/m", 0), pair("c/s", "d/m", 0.5)};
  EXPECT_EQ(resolve_effects(m),
            (std::vector<std::string>{"inertia", "elasticity", "gravity", "dirichlet", "contact_frictionless",
                                      "contact_frictional", "contact_frictional:ball/surface,plate/top",
                                      "contact_frictional:c/s,d/m"}));
}

TEST(ResolveEffects, FrictionlessPairsAloneAddNoFrictionalEntries) {
  Model m;
  m.contact = {pair("a/s", "b/m", 0), pair("c/s", "d/m", 0)};
  EXPECT_EQ(resolve_effects(m), (std::vector<std::string>{"inertia", "elasticity", "contact_frictionless"}));
}

// --- Series layout and the observer fan-out ---------------------------------------------------------

SeriesLayout layout() {
  return SeriesLayout{{{"time", 1, false},
                       {"linear_momentum", 3, false},
                       {"newton_iterations", 1, true},
                       {"angular_momentum", 3, false}}};
}

TEST(SeriesLayout, IndexOfIsTheColumnOffsetOfASeries) {
  const SeriesLayout l = layout();
  EXPECT_EQ(l.index_of("time"), 0);
  EXPECT_EQ(l.index_of("linear_momentum"), 1);
  EXPECT_EQ(l.index_of("newton_iterations"), 4) << "after 1 + 3 components, not the 3rd series' position 2";
  EXPECT_EQ(l.index_of("angular_momentum"), 5);
  EXPECT_EQ(l.index_of("energy"), -1);
  EXPECT_EQ(l.index_of(""), -1);
  EXPECT_EQ(SeriesLayout{}.index_of("time"), -1);
}

TEST(SeriesLayout, RowSizeSumsTheComponents) {
  EXPECT_EQ(layout().row_size(), 8);
  EXPECT_EQ(SeriesLayout{}.row_size(), 0);
}

/// Records the order of calls it receives, prefixed with its name.
class Recorder : public Observer {
 public:
  Recorder(std::string name, std::vector<std::string>& calls) : name_(std::move(name)), calls_(calls) {}
  void begin(const Model&, const SeriesLayout& l) override {
    record("begin " + std::to_string(l.row_size()));
  }
  void step(const StepRow& r) override { record("step " + std::to_string(r.step)); }
  void frame(const Frame& f) override { record("frame " + std::to_string(f.time)); }
  void log(const std::string& line) override { record("log " + line); }
  void end(const Summary& s) override {
    record(std::string("end ") + (s.completed ? "completed" : "stopped"));
  }

 private:
  void record(const std::string& call) { calls_.push_back(name_ + ": " + call); }
  std::string name_;
  std::vector<std::string>& calls_;
};

TEST(ObserverList, PassesEveryCallToEveryObserverInOrder) {
  std::vector<std::string> calls;
  Recorder first("first", calls), second("second", calls);
  ObserverList list({&first, &second});
  list.begin(Model{}, layout());
  list.step(StepRow{3, 0.03, {}});
  list.frame(Frame{0.5, {}, {}, {}, {}, {}});
  list.log("hello");
  Summary summary;
  summary.completed = true;
  list.end(summary);
  EXPECT_EQ(calls,
            (std::vector<std::string>{"first: begin 8", "second: begin 8", "first: step 3", "second: step 3",
                                      "first: frame 0.500000", "second: frame 0.500000", "first: log hello",
                                      "second: log hello", "first: end completed", "second: end completed"}));
}

}  // namespace
}  // namespace stoss::model
