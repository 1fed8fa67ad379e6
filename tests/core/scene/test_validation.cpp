// Requirements for scene validation: every rule of api/scene.schema.json, broken once, is reported
// with its JSON pointer and exact message; several problems are all reported.
#include <gtest/gtest.h>

#include <limits>

#include "core/scene/scene.hpp"
#include "tests/core/scene/scene_issues.hpp"

namespace stoss::scene {
namespace {

using nlohmann::json;

/// A valid scene using every object kind: a hollow sphere, a box, an inline one-element cube.
json full_scene() {
  return json::parse(R"({
    "format": "stoss-scene/1",
    "name": "validation base",
    "bodies": [
      { "name": "ball",
        "mesh": { "hollow_sphere": { "center": [0, 0, 1.3], "outer_radius": 1.0, "inner_radius": 0.8,
                                     "divisions": 2, "layers": 1 } },
        "material": { "youngs_modulus": 1e4, "poisson_ratio": 0.4, "density": 1 },
        "initial_velocity": [0, 1, -1] },
      { "name": "plate",
        "mesh": { "box": { "min": [-2, -2, -0.4], "max": [2, 2, 0], "divisions": [4, 4, 1] } },
        "material": { "youngs_modulus": 1e4, "poisson_ratio": 0.4, "density": 1 } },
      { "name": "cube",
        "mesh": { "nodes": [[5, 0, 0], [6, 0, 0], [6, 1, 0], [5, 1, 0], [5, 0, 1], [6, 0, 1], [6, 1, 1], [5, 1, 1]],
                  "hex8": [[0, 1, 2, 3, 4, 5, 6, 7]],
                  "surfaces": { "top": [[4, 5, 6, 7]] } },
        "material": { "youngs_modulus": 1e4, "poisson_ratio": 0.3, "density": 2 } }
    ],
    "contact": [ { "slave": "ball/outer", "master": "plate/top" } ],
    "boundary": [ { "surface": "plate/bottom", "fix": "xyz" } ],
    "time": { "scheme": "energy_momentum", "step": 0.01, "end": 1.0 },
    "solver": { "tolerance": 1e-10, "max_iterations": 25 },
    "output": { "every": 1 }
  })");
}

/// One change to the base scene: set the value at `path`, or remove the member there.
struct Edit {
  std::string path;
  json value;
  bool remove = false;
};

void apply(json& scene, const Edit& e) {
  const json::json_pointer p(e.path);
  if (e.remove)
    scene[p.parent_pointer()].erase(p.back());
  else
    scene[p] = e.value;
}

using testing::issues_of;

std::string listed(const std::vector<Issue>& issues) {
  std::string out;
  for (const Issue& i : issues) out += "\n  " + i.pointer + ": " + i.message;
  return out;
}

struct Violation {
  const char* rule;
  std::vector<Edit> edits;
  std::string pointer, message;
};

void PrintTo(const Violation& v, std::ostream* os) {
  *os << v.rule;
}

class SceneRule : public ::testing::TestWithParam<Violation> {};

TEST(SceneValidation, BaseSceneIsValid) {
  EXPECT_EQ(listed(issues_of(full_scene())), "");
}

TEST_P(SceneRule, IsReportedWithPointerAndExactMessage) {
  // The validator shall reject a scene that breaks one rule with exactly one issue naming the field
  // by JSON pointer, the rule and the value.
  const Violation& v = GetParam();
  json scene = full_scene();
  for (const Edit& e : v.edits) apply(scene, e);
  const std::vector<Issue> issues = issues_of(scene);
  ASSERT_EQ(issues.size(), 1u) << listed(issues);
  EXPECT_EQ(issues[0].pointer, v.pointer);
  EXPECT_EQ(issues[0].message, v.message);
}

const json unit_cube_upside_down = json::parse("[[4, 5, 6, 7, 0, 1, 2, 3]]");

// clang-format off
INSTANTIATE_TEST_SUITE_P(Rules, SceneRule, ::testing::Values(
  // top level
  Violation{"format required", {{"/format", nullptr, true}}, "/format", "required"},
  Violation{"format value", {{"/format", "stoss-scene/2"}}, "/format", R"(must be "stoss-scene/1", got "stoss-scene/2")"},
  Violation{"name type", {{"/name", 5}}, "/name", "must be a string, got 5"},
  Violation{"unknown top-level field", {{"/damping", 0.1}}, "/damping", "unknown field"},
  Violation{"bodies required", {{"/bodies", nullptr, true}, {"/contact", json::array()}, {"/boundary", json::array()}},
            "/bodies", "required"},
  Violation{"bodies non-empty", {{"/bodies", json::array()}, {"/contact", json::array()}, {"/boundary", json::array()}},
            "/bodies", "must be a non-empty array, got []"},
  Violation{"contact array", {{"/contact", json::object()}}, "/contact", "must be an array, got {}"},
  Violation{"gravity vector", {{"/gravity", {0, -9.81}}}, "/gravity", "must be an array of 3 numbers, got [0,-9.81]"},
  // bodies
  Violation{"body name pattern", {{"/bodies/2/name", "my cube"}}, "/bodies/2/name",
            R"(must match [A-Za-z0-9_-]+, got "my cube")"},
  Violation{"body name unique", {{"/bodies/2/name", "plate"}}, "/bodies/2/name",
            R"(must be unique, got "plate" (also /bodies/1/name))"},
  Violation{"body name required", {{"/bodies/2/name", nullptr, true}}, "/bodies/2/name", "required"},
  Violation{"unknown body field", {{"/bodies/0/colour", "red"}}, "/bodies/0/colour", "unknown field"},
  Violation{"initial velocity", {{"/bodies/0/initial_velocity", {0, 1}}}, "/bodies/0/initial_velocity",
            "must be an array of 3 numbers, got [0,1]"},
  Violation{"angular velocity numbers", {{"/bodies/0/initial_angular_velocity", {0, "1", 0}}},
            "/bodies/0/initial_angular_velocity", R"(must be an array of 3 numbers, got [0,"1",0])"},
  Violation{"center vector", {{"/bodies/0/center", 1.3}}, "/bodies/0/center", "must be an array of 3 numbers, got 1.3"},
  // material
  Violation{"material required", {{"/bodies/1/material", nullptr, true}}, "/bodies/1/material", "required"},
  Violation{"poisson ratio", {{"/bodies/1/material/poisson_ratio", 0.5}}, "/bodies/1/material/poisson_ratio",
            "must be in (-1, 0.5), got 0.5"},
  Violation{"poisson ratio low", {{"/bodies/1/material/poisson_ratio", -1}}, "/bodies/1/material/poisson_ratio",
            "must be in (-1, 0.5), got -1"},
  Violation{"youngs modulus", {{"/bodies/1/material/youngs_modulus", -1e4}}, "/bodies/1/material/youngs_modulus",
            "must be > 0, got -10000.0"},
  Violation{"density required", {{"/bodies/1/material/density", nullptr, true}}, "/bodies/1/material/density",
            "required"},
  Violation{"density type", {{"/bodies/1/material/density", "1"}}, "/bodies/1/material/density",
            R"(must be a number, got "1")"},
  Violation{"material model", {{"/bodies/1/material/model", "mooney_rivlin"}}, "/bodies/1/material/model",
            R"(must be one of saint_venant_kirchhoff, neo_hookean, got "mooney_rivlin")"},
  // mesh kinds
  Violation{"mesh required", {{"/bodies/0/mesh", nullptr, true}}, "/bodies/0/mesh", "required"},
  Violation{"mesh two kinds", {{"/bodies/0/mesh/box", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}, {"divisions", {1, 1, 1}}}}},
            "/bodies/0/mesh", "exactly one of box, hollow_sphere, nodes+hex8, file, id"},
  Violation{"mesh no kind", {{"/bodies/0/mesh", json::object()}}, "/bodies/0/mesh",
            "exactly one of box, hollow_sphere, nodes+hex8, file, id"},
  Violation{"unknown mesh field", {{"/bodies/1/mesh/cylinder", json::object()}}, "/bodies/1/mesh/cylinder", "unknown field"},
  // box
  Violation{"box max > min", {{"/bodies/1/mesh/box/max", {2, -3, 0}}}, "/bodies/1/mesh/box/max",
            "must be > min componentwise, got [2,-3,0]"},
  Violation{"box min required", {{"/bodies/1/mesh/box/min", nullptr, true}}, "/bodies/1/mesh/box/min", "required"},
  Violation{"box divisions >= 1", {{"/bodies/1/mesh/box/divisions", {4, 0, 1}}}, "/bodies/1/mesh/box/divisions/1",
            "must be >= 1, got 0"},
  Violation{"box divisions integer", {{"/bodies/1/mesh/box/divisions", {4, 1.5, 1}}}, "/bodies/1/mesh/box/divisions/1",
            "must be an integer, got 1.5"},
  Violation{"box divisions three", {{"/bodies/1/mesh/box/divisions", {4, 4}}}, "/bodies/1/mesh/box/divisions",
            "must be an array of 3 integers, got [4,4]"},
  Violation{"box node limit", {{"/bodies/1/mesh/box/divisions", {1000, 1000, 1000}}}, "/bodies/1/mesh/box/divisions",
            "must give at most 10000000 nodes, got 1003003001"},
  // hollow sphere
  Violation{"outer > inner", {{"/bodies/0/mesh/hollow_sphere/outer_radius", 0.5}},
            "/bodies/0/mesh/hollow_sphere/outer_radius", "must be > inner_radius (0.8), got 0.5"},
  Violation{"inner > 0", {{"/bodies/0/mesh/hollow_sphere/inner_radius", 0}}, "/bodies/0/mesh/hollow_sphere/inner_radius",
            "must be > 0, got 0"},
  Violation{"outer required", {{"/bodies/0/mesh/hollow_sphere/outer_radius", nullptr, true}},
            "/bodies/0/mesh/hollow_sphere/outer_radius", "required"},
  Violation{"sphere divisions", {{"/bodies/0/mesh/hollow_sphere/divisions", 0}},
            "/bodies/0/mesh/hollow_sphere/divisions", "must be >= 1, got 0"},
  Violation{"sphere layers", {{"/bodies/0/mesh/hollow_sphere/layers", "two"}}, "/bodies/0/mesh/hollow_sphere/layers",
            R"(must be an integer, got "two")"},
  Violation{"sphere node limit", {{"/bodies/0/mesh/hollow_sphere/divisions", 1000}}, "/bodies/0/mesh/hollow_sphere",
            "must give at most 10000000 nodes, got 12000004"},
  Violation{"unknown sphere field", {{"/bodies/0/mesh/hollow_sphere/radius", 1}}, "/bodies/0/mesh/hollow_sphere/radius",
            "unknown field"},
  // inline mesh
  Violation{"hex8 required", {{"/bodies/2/mesh/hex8", nullptr, true}}, "/bodies/2/mesh/hex8", "required"},
  Violation{"node index range", {{"/bodies/2/mesh/hex8/0/3", 8}}, "/bodies/2/mesh/hex8/0/3", "must be in [0, 7], got 8"},
  Violation{"hex8 row size", {{"/bodies/2/mesh/hex8/0", {0, 1, 2, 3}}}, "/bodies/2/mesh/hex8/0",
            "must be an array of 8 node indices, got [0,1,2,3]"},
  Violation{"node coordinates", {{"/bodies/2/mesh/nodes/1", {6, 0}}}, "/bodies/2/mesh/nodes/1",
            "must be an array of 3 numbers, got [6,0]"},
  Violation{"inverted element", {{"/bodies/2/mesh/hex8", unit_cube_upside_down}}, "/bodies/2/mesh/hex8/0",
            "det J0 must be > 0 at every Gauss point, got -0.125"},
  Violation{"surface row size", {{"/bodies/2/mesh/surfaces/top/0", {4, 5, 6}}}, "/bodies/2/mesh/surfaces/top/0",
            "must be an array of 4 node indices, got [4,5,6]"},
  Violation{"surface index range", {{"/bodies/2/mesh/surfaces/top/0/2", -1}}, "/bodies/2/mesh/surfaces/top/0/2",
            "must be in [0, 7], got -1"},
  Violation{"surface name", {{"/bodies/2/mesh/surfaces", {{"a/b", {{4, 5, 6, 7}}}}}}, "/bodies/2/mesh/surfaces/a~1b",
            R"(must match [A-Za-z0-9_-]+, got "a/b")"},
  // contact
  Violation{"slave required", {{"/contact/0/slave", nullptr, true}}, "/contact/0/slave", "required"},
  Violation{"surface reference form", {{"/contact/0/slave", "ball"}}, "/contact/0/slave",
            R"(must be of the form body/surface, got "ball")"},
  Violation{"surface reference body", {{"/contact/0/master", "table/top"}}, "/contact/0/master",
            R"(no body named "table")"},
  Violation{"surface reference surface", {{"/contact/0/master", "plate/side"}}, "/contact/0/master",
            R"(body "plate" has no surface "side" (it has bottom, boundary, top, xmax, xmin, ymax, ymin))"},
  Violation{"inline surfaces include boundary", {{"/contact/0/master", "cube/bottom"}}, "/contact/0/master",
            R"(body "cube" has no surface "bottom" (it has boundary, top))"},
  Violation{"slave and master bodies differ", {{"/contact/0/master", "ball/inner"}}, "/contact/0/master",
            R"(must be on another body than slave, got "ball/inner")"},
  Violation{"friction needs penalty", {{"/contact/0/friction", 0.3}, {"/contact/0/enforcement", "lagrange"}},
            "/contact/0/enforcement", R"(friction > 0 requires enforcement "penalty")"},
  Violation{"friction >= 0", {{"/contact/0/friction", -0.1}}, "/contact/0/friction", "must be >= 0, got -0.1"},
  Violation{"enforcement value", {{"/contact/0/enforcement", "mortar"}}, "/contact/0/enforcement",
            R"(must be one of lagrange, penalty, got "mortar")"},
  Violation{"discretization value", {{"/contact/0/discretization", "segment_to_segment"}}, "/contact/0/discretization",
            R"(must be one of node_to_segment, mortar, got "segment_to_segment")"},
  Violation{"mortar is frictionless", {{"/contact/0/discretization", "mortar"}, {"/contact/0/friction", 0.3}}, "/contact/0",
            R"(discretization "mortar" is frictionless (friction on mortar is not implemented): friction must be 0 with it, got 0.3; use discretization "node_to_segment" for friction)"},
  Violation{"mortar is lagrange", {{"/contact/0/discretization", "mortar"}, {"/contact/0/enforcement", "penalty"}}, "/contact/0",
            R"(discretization "mortar" enforces contact with Lagrange multipliers: enforcement must be "lagrange" with it, got "penalty")"},
  Violation{"mortar is faceted", {{"/contact/0/discretization", "mortar"}, {"/contact/0/master_surface", "smooth"}}, "/contact/0",
            R"(discretization "mortar" integrates on the faceted master surface (the mesh's bilinear faces, docs/theory.md §4.7): master_surface must be "faceted" or absent with it, got "smooth")"},
  Violation{"velocity correction needs EM",
            {{"/contact/0/impact", "velocity_correction"}, {"/time/scheme", "midpoint"}}, "/contact/0/impact",
            R"("velocity_correction" needs time.scheme "energy_momentum", got "midpoint")"},
  Violation{"impact mode", {{"/contact/0/impact", "bounce"}}, "/contact/0/impact",
            R"(must be one of persist, exact, velocity_correction, located, got "bounce")"},
  Violation{"switch hysteresis", {{"/contact/0/switch_hysteresis", -0.05}}, "/contact/0/switch_hysteresis",
            "must be >= 0, got -0.05"},
  Violation{"switch gap rule", {{"/contact/0/switch_gap", "snap"}}, "/contact/0/switch_gap",
            R"(must be one of clamp, keep, got "snap")"},
  Violation{"normal stiffness", {{"/contact/0/normal_stiffness", 0}}, "/contact/0/normal_stiffness",
            "must be > 0, got 0"},
  Violation{"tangential stiffness", {{"/contact/0/tangential_stiffness", -1}}, "/contact/0/tangential_stiffness",
            "must be > 0, got -1"},
  Violation{"normal traction", {{"/contact/0/normal_traction", "average"}}, "/contact/0/normal_traction",
            R"(must be one of discrete_derivative, midpoint, got "average")"},
  Violation{"unknown contact field", {{"/contact/0/mu", 0.2}}, "/contact/0/mu", "unknown field"},
  // boundary
  Violation{"boundary surface required", {{"/boundary/0/surface", nullptr, true}}, "/boundary/0/surface", "required"},
  Violation{"boundary surface exists", {{"/boundary/0/surface", "plate/base"}}, "/boundary/0/surface",
            R"(body "plate" has no surface "base" (it has bottom, boundary, top, xmax, xmin, ymax, ymin))"},
  Violation{"fix distinct", {{"/boundary/0/fix", "xx"}}, "/boundary/0/fix", R"(must be distinct letters from "xyz", got "xx")"},
  Violation{"fix letters", {{"/boundary/0/fix", "xw"}}, "/boundary/0/fix", R"(must be distinct letters from "xyz", got "xw")"},
  Violation{"fix non-empty", {{"/boundary/0/fix", ""}}, "/boundary/0/fix", R"(must be distinct letters from "xyz", got "")"},
  // time, solver, output
  Violation{"time required", {{"/time", nullptr, true}}, "/time", "required"},
  Violation{"step required", {{"/time/step", nullptr, true}}, "/time/step", "required"},
  Violation{"step > 0", {{"/time/step", -0.01}}, "/time/step", "must be > 0, got -0.01"},
  Violation{"end required", {{"/time/end", nullptr, true}}, "/time/end", "required"},
  Violation{"end >= step", {{"/time/step", 0.1}, {"/time/end", 0.05}}, "/time/end", "must be >= step (0.1), got 0.05"},
  Violation{"step count", {{"/time/step", 1e-12}, {"/time/end", 10}}, "/time/step",
            "must give at most 1e9 steps, got end / step = 10000000000000"},
  Violation{"scheme value", {{"/time/scheme", "rk4"}}, "/time/scheme",
            R"(must be one of energy_momentum, midpoint, hht, generalized_alpha, static, got "rk4")"},
  Violation{"rho_infinity range", {{"/time/scheme", "generalized_alpha"}, {"/time/rho_infinity", 1.5}},
            "/time/rho_infinity", "must be in [0, 1], got 1.5"},
  Violation{"penalty with generalized_alpha",
            {{"/time/scheme", "generalized_alpha"}, {"/contact/0/enforcement", "penalty"}}, "/contact/0/enforcement",
            R"("penalty" is not implemented with time.scheme "generalized_alpha"; use energy_momentum or midpoint)"},
  Violation{"alpha range", {{"/time/scheme", "hht"}, {"/time/alpha", 0.1}}, "/time/alpha",
            "must be in [-1/3, 0], got 0.1"},
  Violation{"unknown time field", {{"/time/dt", 0.01}}, "/time/dt", "unknown field"},
  Violation{"tolerance range", {{"/solver/tolerance", 0.01}}, "/solver/tolerance", "must be in (0, 1e-3], got 0.01"},
  Violation{"tolerance positive", {{"/solver/tolerance", 0}}, "/solver/tolerance", "must be in (0, 1e-3], got 0"},
  Violation{"max iterations range", {{"/solver/max_iterations", 300}}, "/solver/max_iterations",
            "must be in [1, 200], got 300"},
  Violation{"max iterations integer", {{"/solver/max_iterations", 2.5}}, "/solver/max_iterations",
            "must be an integer, got 2.5"},
  Violation{"solver object", {{"/solver", "newton"}}, "/solver", R"(must be an object, got "newton")"},
  Violation{"linear solver name", {{"/solver/linear", "amg"}}, "/solver/linear",
            R"(must be one of auto, direct, iterative, petsc_gamg, got "amg")"},
  Violation{"ranks at least 1", {{"/solver/ranks", 0}}, "/solver/ranks", "must be in [1, 4096], got 0"},
  Violation{"ranks at most 4096", {{"/solver/ranks", 4097}}, "/solver/ranks", "must be in [1, 4096], got 4097"},
  Violation{"ranks integer", {{"/solver/ranks", 2.5}}, "/solver/ranks", "must be an integer, got 2.5"},
  Violation{"ranks number", {{"/solver/ranks", "two"}}, "/solver/ranks", R"(must be an integer, got "two")"},
  Violation{"iterative on several ranks",
            {{"/solver/ranks", 2}, {"/solver/linear", "iterative"}},
            "/solver/linear",
            R"("iterative" solves on one rank; with solver.ranks 2 it must be "petsc_gamg", "direct" (MUMPS) or "auto")"},
  Violation{"output every", {{"/output/every", 0}}, "/output/every", "must be >= 1, got 0"},
  // steps chosen by a tolerance, frames at an interval (issue 22 "Bad input")
  Violation{"time tolerance > 0", {{"/time/tolerance", 0}}, "/time/tolerance", "must be > 0, got 0"},
  Violation{"time tolerance negative", {{"/time/tolerance", -1e-3}}, "/time/tolerance", "must be > 0, got -0.001"},
  Violation{"time tolerance finite", {{"/time/tolerance", std::numeric_limits<double>::infinity()}}, "/time/tolerance",
            "must be a number, got null"},
  Violation{"min_step without tolerance", {{"/time/min_step", 1e-4}}, "/time/min_step",
            "is allowed only with time.tolerance (steps chosen by a tolerance)"},
  Violation{"max_step without tolerance", {{"/time/max_step", 0.1}}, "/time/max_step",
            "is allowed only with time.tolerance (steps chosen by a tolerance)"},
  Violation{"min_step <= max_step", {{"/time/tolerance", 1e-3}, {"/time/min_step", 0.02}, {"/time/max_step", 0.01}},
            "/time/min_step", "must be <= max_step (0.01), got 0.02"},
  Violation{"min_step < end", {{"/time/tolerance", 1e-3}, {"/time/min_step", 1.0}, {"/time/max_step", 2.0}},
            "/time/min_step", "must be < end (1.0), got 1.0"},
  Violation{"step >= min_step", {{"/time/tolerance", 1e-3}, {"/time/min_step", 0.02}}, "/time/step",
            "must be in [min_step, max_step] = [0.02, 1.0] (the first step), got 0.01"},
  Violation{"step <= max_step", {{"/time/tolerance", 1e-3}, {"/time/max_step", 0.005}}, "/time/step",
            "must be in [min_step, max_step] = [9.765625e-06, 0.005] (the first step), got 0.01"},
  Violation{"min_step > 0", {{"/time/tolerance", 1e-3}, {"/time/min_step", 0}}, "/time/min_step", "must be > 0, got 0"},
  Violation{"output interval > 0", {{"/output/every", nullptr, true}, {"/output/interval", 0}}, "/output/interval",
            "must be > 0, got 0"},
  Violation{"output interval finite", {{"/output/every", nullptr, true}, {"/output/interval", -0.5}}, "/output/interval",
            "must be > 0, got -0.5"},
  Violation{"every with interval", {{"/output/interval", 0.1}}, "/output/interval",
            "cannot be given together with output.every: frames come at times (interval) or every so many steps "
            "(every), not both"}));
// clang-format on

// With a tolerance, min_step and max_step get their defaults step/1024 and end in the resolved scene and the
// model; the dry run counts end/min_step steps and, with an interval, end/interval + 1 frames (the server's
// limits use these counts).
TEST(SceneValidation, ATolerancesStepBoundsAndAnIntervalsFramesAreResolved) {
  json scene = full_scene();
  apply(scene, {"/time/tolerance", 1e-3});
  apply(scene, {"/output/every", nullptr, true});
  apply(scene, {"/output/interval", 0.25});
  const model::Model m = load(scene);
  ASSERT_TRUE(m.time.tolerance.has_value());
  EXPECT_EQ(*m.time.tolerance, 1e-3);
  EXPECT_EQ(m.time.min_step, 0.01 / 1024);
  EXPECT_EQ(m.time.max_step, 1.0);
  EXPECT_EQ(m.scene["time"]["min_step"].get<double>(), 0.01 / 1024);
  ASSERT_TRUE(m.output.interval.has_value());
  EXPECT_EQ(*m.output.interval, 0.25);
  const Summary s = summarize(m);
  EXPECT_EQ(s.steps, 102404) << "end/min_step, and a landing step per frame";
  EXPECT_EQ(s.frames, 5);
  // Without a tolerance the scene gets neither bound.
  const model::Model fixed = load(full_scene());
  EXPECT_FALSE(fixed.time.adaptive());
  EXPECT_FALSE(fixed.scene["time"].contains("min_step"));
}

// solver.ranks (issue 27 §5): read into the model; absent means one rank and is not filled in, so the
// resolved scene (and the digests of results written from it) of a scene without it does not change.
TEST(SceneValidation, SolverRanksIsReadAndAbsentIsOneRankNotFilledIn) {
  const model::Model one = load(full_scene());
  EXPECT_EQ(one.solver.ranks, 1);
  EXPECT_FALSE(one.scene["solver"].contains("ranks")) << one.scene["solver"].dump();
  json scene = full_scene();
  apply(scene, {"/solver/ranks", 2});
  const model::Model two = load(scene);
  EXPECT_EQ(two.solver.ranks, 2);
  EXPECT_EQ(two.scene["solver"]["ranks"], 2);
  EXPECT_EQ(load_resolved(two.scene, MeshFiles{}).solver.ranks, 2) << "the worker's path reads it too";
  apply(scene, {"/solver/ranks", 4.0});  // an integral number, as every integer field takes it
  EXPECT_EQ(load(scene).solver.ranks, 4);
}

TEST(SceneValidation, ReportsEveryProblemAtOnce) {
  // The validator shall report all problems of a scene, not only the first, in one SceneError whose
  // what() lists them one per line.
  json scene = full_scene();
  for (const Edit& e : std::vector<Edit>{{"/bodies/1/material/poisson_ratio", 0.5},
                                         {"/bodies/0/extra", true},
                                         {"/contact/0/friction", 0.2},
                                         {"/contact/0/enforcement", "lagrange"},
                                         {"/time/step", nullptr, true},
                                         {"/output/every", 0}})
    apply(scene, e);
  try {
    load(scene);
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    const std::vector<std::pair<std::string, std::string>> expected{
        {"/bodies/0/extra", "unknown field"},
        {"/bodies/1/material/poisson_ratio", "must be in (-1, 0.5), got 0.5"},
        {"/contact/0/enforcement", R"(friction > 0 requires enforcement "penalty")"},
        {"/time/step", "required"},
        {"/output/every", "must be >= 1, got 0"}};
    ASSERT_EQ(e.issues.size(), expected.size()) << listed(e.issues);
    for (size_t i = 0; i < expected.size(); ++i) {
      EXPECT_EQ(e.issues[i].pointer, expected[i].first);
      EXPECT_EQ(e.issues[i].message, expected[i].second);
    }
    EXPECT_STREQ(e.what(),
                 "/bodies/0/extra: unknown field\n"
                 "/bodies/1/material/poisson_ratio: must be in (-1, 0.5), got 0.5\n"
                 "/contact/0/enforcement: friction > 0 requires enforcement \"penalty\"\n"
                 "/time/step: required\n"
                 "/output/every: must be >= 1, got 0");
  }
}

TEST(SceneValidation, ReportsEveryBadElementOfAnInlineMesh) {
  json scene = full_scene();
  apply(scene, {"/bodies/2/mesh/hex8/0/3", 8});
  apply(scene, {"/bodies/2/mesh/hex8/0/5", 9});
  apply(scene, {"/bodies/2/mesh/nodes/4", {5, 0}});
  const std::vector<Issue> issues = issues_of(scene);
  ASSERT_EQ(issues.size(), 3u) << listed(issues);
  EXPECT_EQ(issues[0].pointer, "/bodies/2/mesh/nodes/4");
  EXPECT_EQ(issues[1].pointer, "/bodies/2/mesh/hex8/0/3");
  EXPECT_EQ(issues[2].pointer, "/bodies/2/mesh/hex8/0/5");
}

TEST(SceneValidation, ANonObjectSceneIsOneIssueAtTheRoot) {
  const std::vector<Issue> issues = issues_of(json::array());
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].pointer, "");
  EXPECT_EQ(issues[0].message, "must be an object, got []");
  try {
    load(json::array());
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "must be an object, got []");
  }
}

TEST(SceneValidation, UnknownFieldsAreReportedEverywhere) {
  json scene = full_scene();
  for (const char* path :
       {"/x", "/bodies/0/x", "/bodies/0/mesh/x", "/bodies/0/mesh/hollow_sphere/x", "/bodies/1/mesh/box/x",
        "/bodies/1/material/x", "/contact/0/x", "/boundary/0/x", "/time/x", "/solver/x", "/output/x"})
    apply(scene, {path, 1});
  const std::vector<Issue> issues = issues_of(scene);
  EXPECT_EQ(issues.size(), 11u) << listed(issues);
  for (const Issue& i : issues) EXPECT_EQ(i.message, "unknown field") << i.pointer;
}

TEST(SceneValidation, PointersEscapeTildeAndSlash) {
  json scene = full_scene();
  apply(scene, {"/bodies/0/a~1b~0c", 1});
  const std::vector<Issue> issues = issues_of(scene);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].pointer, "/bodies/0/a~1b~0c");
}

}  // namespace
}  // namespace stoss::scene
