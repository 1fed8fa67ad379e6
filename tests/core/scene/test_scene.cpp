// Requirements for loading scenes: defaults, the Model built from them, resolved effects, example
// scenes, files, and agreement between the C++ defaults and api/scene.schema.json.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "core/scene/scene.hpp"

namespace stoss::scene {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

const json material = {{"youngs_modulus", 1e4}, {"poisson_ratio", 0.4}, {"density", 1}};

/// The least a scene must say: one hollow sphere (every generator default) and a time span.
json minimal_scene() {
  return {{"format", "stoss-scene/1"},
          {"bodies",
           {{{"name", "ball"},
             {"mesh", {{"hollow_sphere", {{"outer_radius", 1.0}, {"inner_radius", 0.8}}}}},
             {"material", material}}}},
          {"time", {{"step", 0.01}, {"end", 1.0}}}};
}

json plate() {
  return {{"name", "plate"},
          {"mesh", {{"box", {{"min", {-2, -2, -0.4}}, {"max", {2, 2, 0}}, {"divisions", {4, 4, 1}}}}}},
          {"material", material}};
}

json with_plate(json scene) {
  scene["bodies"].push_back(plate());
  return scene;
}

std::vector<std::string> effects_of(const json& scene) {
  return load(scene).effects;
}

using Effects = std::vector<std::string>;

// ------------------------------------------------------------------------------------ valid scenes

TEST(SceneLoad, MinimalSceneGetsEveryDefault) {
  // A scene with only the required fields shall load, with the defaults of api/scene.schema.json.
  const model::Model m = load(minimal_scene());
  EXPECT_EQ(m.name, "unnamed");
  EXPECT_EQ(m.mesh.node_count(), 654);
  EXPECT_EQ(m.mesh.element_count(), 432);
  ASSERT_EQ(m.bodies.size(), 1u);
  const model::BodySpec& ball = m.bodies[0];
  EXPECT_EQ(ball.name, "ball");
  EXPECT_EQ(ball.material.model, "saint_venant_kirchhoff");
  EXPECT_EQ(ball.material.youngs_modulus, 1e4);
  EXPECT_EQ(ball.material.poisson_ratio, 0.4);
  EXPECT_EQ(ball.material.density, 1);
  EXPECT_EQ(ball.initial_velocity, Eigen::Vector3d::Zero());
  EXPECT_EQ(ball.initial_angular_velocity, Eigen::Vector3d::Zero());
  EXPECT_FALSE(ball.center.has_value());
  EXPECT_TRUE(m.contact.empty());
  EXPECT_TRUE(m.boundary.empty());
  EXPECT_FALSE(m.gravity.has_value());
  EXPECT_EQ(m.time.scheme, model::Scheme::energy_momentum);
  EXPECT_EQ(m.time.step, 0.01);
  EXPECT_EQ(m.time.end, 1.0);
  EXPECT_EQ(m.time.steps(), 100);
  EXPECT_EQ(m.solver.tolerance, 1e-10);
  EXPECT_EQ(m.solver.max_iterations, 25);
  EXPECT_EQ(m.output.every, 1);
  EXPECT_EQ(m.effects, (Effects{"inertia", "elasticity"}));
}

TEST(SceneLoad, SceneCopyHasDefaultsFilledIn) {
  const json s = load(minimal_scene()).scene;
  EXPECT_EQ(s["name"], "unnamed");
  EXPECT_EQ(s["contact"], json::array());
  EXPECT_EQ(s["boundary"], json::array());
  EXPECT_EQ(s["gravity"], json({0, 0, 0}));
  EXPECT_EQ(s["time"], json({{"scheme", "energy_momentum"}, {"step", 0.01}, {"end", 1.0}}));
  EXPECT_EQ(s["solver"], json({{"tolerance", 1e-10}, {"max_iterations", 25}, {"linear", "auto"}}));
  EXPECT_EQ(s["output"], json({{"every", 1}, {"checkpoint_seconds", 60.0}}));
  const json& ball = s["bodies"][0];
  EXPECT_EQ(ball["mesh"]["hollow_sphere"], json({{"center", {0, 0, 0}},
                                                 {"outer_radius", 1.0},
                                                 {"inner_radius", 0.8},
                                                 {"divisions", 6},
                                                 {"layers", 2}}));
  EXPECT_EQ(ball["material"]["model"], "saint_venant_kirchhoff");
  EXPECT_EQ(ball["initial_velocity"], json({0, 0, 0}));
  EXPECT_EQ(ball["initial_angular_velocity"], json({0, 0, 0}));
  EXPECT_FALSE(ball.contains("center"));
}

TEST(SceneLoad, BodiesAreMeshedInOrderWithTheirSurfaces) {
  json scene = with_plate(minimal_scene());
  scene["bodies"][0]["center"] = {0, 0, 1.3};
  scene["bodies"][0]["initial_angular_velocity"] = {0, 0, 2};
  const model::Model m = load(scene);
  ASSERT_EQ(m.mesh.bodies.size(), 2u);
  const mesh::Body& ball = m.mesh.bodies[0];
  const mesh::Body& box = m.mesh.bodies[1];
  EXPECT_EQ(ball.name, "ball");
  EXPECT_EQ(ball.node_end, 654);
  EXPECT_EQ(box.node_begin, 654);
  EXPECT_EQ(box.node_end, 654 + 5 * 5 * 2);
  EXPECT_EQ(box.element_begin, 432);
  EXPECT_EQ(m.mesh.element_count(), 432 + 16);
  EXPECT_EQ(m.mesh.surface_nodes("ball/outer").size(), 218u);
  EXPECT_EQ(m.mesh.surface("plate/top").size(), 16u);
  EXPECT_EQ(*m.bodies[0].center, Eigen::Vector3d(0, 0, 1.3));
  EXPECT_EQ(m.bodies[0].initial_angular_velocity, Eigen::Vector3d(0, 0, 2));
  EXPECT_EQ(m.bodies[1].name, "plate");
}

TEST(SceneLoad, InlineMeshGetsItsBoundarySurface) {
  json scene = minimal_scene();
  scene["bodies"][0]["mesh"] = json::parse(R"({
    "nodes": [[0,0,0],[1,0,0],[1,1,0],[0,1,0],[0,0,1],[1,0,1],[1,1,1],[0,1,1],[2,0,0],[2,1,0],[2,0,1],[2,1,1]],
    "hex8": [[0,1,2,3,4,5,6,7],[1,8,9,2,5,10,11,6]],
    "surfaces": { "end": [[8,9,11,10]] } })");
  const model::Model m = load(scene);
  EXPECT_EQ(m.mesh.node_count(), 12);
  EXPECT_EQ(m.mesh.surface("ball/boundary").size(), 10u);
  EXPECT_EQ(m.mesh.surface("ball/end").size(), 1u);
  EXPECT_EQ(m.scene["bodies"][0]["mesh"]["surfaces"].size(),
            1u);  // "boundary" is the mesh's, not the scene's
}

TEST(SceneLoad, ContactBoundaryAndTimeOptionsReachTheModel) {
  json scene = with_plate(minimal_scene());
  scene["contact"] = {{{"slave", "ball/outer"},
                       {"master", "plate/top"},
                       {"friction", 0.2},
                       {"impact", "exact"},
                       {"switch_hysteresis", 0.1},
                       {"switch_gap", "keep"},
                       {"normal_stiffness", 2.5e4},
                       {"normal_traction", "midpoint"}}};
  scene["boundary"] = {{{"surface", "plate/bottom"}, {"fix", "zx"}}};
  scene["gravity"] = {0, 0, -9.81};
  scene["time"] = {{"scheme", "midpoint"}, {"step", 0.05}, {"end", 2.0}};  // penalty has no hht form
  const model::Model m = load(scene);
  ASSERT_EQ(m.contact.size(), 1u);
  const model::ContactPair& c = m.contact[0];
  EXPECT_EQ(c.slave, "ball/outer");
  EXPECT_EQ(c.master, "plate/top");
  EXPECT_EQ(c.enforcement, model::Enforcement::penalty);  // the default when friction > 0
  EXPECT_EQ(c.friction, 0.2);
  EXPECT_EQ(c.impact, model::ImpactMode::exact);
  EXPECT_EQ(c.switch_hysteresis, 0.1);
  EXPECT_EQ(c.switch_gap, model::SwitchGap::keep);
  EXPECT_EQ(c.normal_stiffness, 2.5e4);
  EXPECT_FALSE(c.tangential_stiffness.has_value());
  EXPECT_EQ(c.normal_traction, model::NormalTraction::midpoint);
  EXPECT_EQ(m.scene["contact"][0]["enforcement"], "penalty");
  ASSERT_EQ(m.boundary.size(), 1u);
  EXPECT_EQ(m.boundary[0].surface, "plate/bottom");
  EXPECT_EQ(m.boundary[0].fix, (std::array<bool, 3>{true, false, true}));
  EXPECT_EQ(*m.gravity, Eigen::Vector3d(0, 0, -9.81));
  EXPECT_EQ(m.time.scheme, model::Scheme::midpoint);
  EXPECT_EQ(m.time.steps(), 40);
}

TEST(SceneLoad, AlphaIsFilledInForHhtOnly) {
  EXPECT_FALSE(load(minimal_scene()).scene["time"].contains("alpha"));
  json scene = minimal_scene();
  scene["time"]["scheme"] = "midpoint";
  EXPECT_EQ(load(scene).time.scheme, model::Scheme::midpoint);
  EXPECT_FALSE(load(scene).scene["time"].contains("alpha"));
}

TEST(SceneLoad, IntegralNumbersAreAcceptedAsIntegers) {
  json scene = minimal_scene();
  scene["bodies"][0]["mesh"]["hollow_sphere"]["divisions"] = 3.0;
  scene["output"] = {{"every", 10.0}};
  const model::Model m = load(scene);
  EXPECT_EQ(m.mesh.element_count(), 6 * 9 * 2);
  EXPECT_TRUE(m.scene["output"]["every"].is_number_integer());
  EXPECT_EQ(m.output.every, 10);
}

// ---------------------------------------------------------------------------------------- effects

TEST(SceneEffects, InertiaAndElasticityAlways) {
  EXPECT_EQ(effects_of(minimal_scene()), (Effects{"inertia", "elasticity"}));
}

TEST(SceneEffects, GravityOnlyWhenNonZero) {
  json scene = minimal_scene();
  scene["gravity"] = {0, 0, 0};
  EXPECT_EQ(effects_of(scene), (Effects{"inertia", "elasticity"}));
  scene["gravity"] = {0, 0, -9.81};
  EXPECT_EQ(effects_of(scene), (Effects{"inertia", "elasticity", "gravity"}));
}

TEST(SceneEffects, BoundaryMeansDirichlet) {
  json scene = with_plate(minimal_scene());
  scene["boundary"] = {{{"surface", "plate/bottom"}}};
  EXPECT_EQ(effects_of(scene), (Effects{"inertia", "elasticity", "dirichlet"}));
}

TEST(SceneEffects, FrictionlessAndFrictionalContact) {
  json scene = with_plate(minimal_scene());
  scene["contact"] = {{{"slave", "ball/outer"}, {"master", "plate/top"}}};
  EXPECT_EQ(effects_of(scene), (Effects{"inertia", "elasticity", "contact_frictionless"}));
  scene["contact"][0]["friction"] = 0.2;
  EXPECT_EQ(effects_of(scene), (Effects{"inertia", "elasticity", "contact_frictional",
                                        "contact_frictional:ball/outer,plate/top"}));
}

TEST(SceneEffects, TheEffectListNamesEachFrictionalPair) {
  json scene = with_plate(minimal_scene());
  scene["contact"] = {{{"slave", "ball/outer"}, {"master", "plate/top"}},
                      {{"slave", "plate/top"}, {"master", "ball/outer"}, {"friction", 0.3}}};
  EXPECT_EQ(effects_of(scene), (Effects{"inertia", "elasticity", "contact_frictionless", "contact_frictional",
                                        "contact_frictional:plate/top,ball/outer"}));
}

// ------------------------------------------------------------------------------- files, examples

std::string write_file(const std::string& name, const std::string& text) {
  const fs::path path = fs::temp_directory_path() / (std::to_string(::getpid()) + "_" + name);
  std::ofstream(path) << text;
  return path.string();
}

TEST(SceneFile, MalformedJsonNamesLineAndColumn) {
  const std::string path = write_file("stoss_scene_test_malformed.json",
                                      "{\n  \"format\": \"stoss-scene/1\",\n  \"bodies\" []\n}\n");
  try {
    load_file(path);
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    ASSERT_EQ(e.issues.size(), 1u);
    EXPECT_EQ(e.issues[0].pointer, "");
    EXPECT_EQ(
        e.issues[0].message,
        "parse error at line 3, column 12: syntax error while parsing object separator - unexpected '['; "
        "expected ':'");
  }
  fs::remove(path);
}

TEST(SceneFile, UnreadableFileIsASceneError) {
  try {
    load_file("/nonexistent/stoss/scene.json");
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    ASSERT_EQ(e.issues.size(), 1u);
    EXPECT_EQ(e.issues[0].pointer, "");
    EXPECT_EQ(e.issues[0].message, "cannot read /nonexistent/stoss/scene.json: No such file or directory");
  }
}

TEST(SceneFile, ValidationErrorsOfAFileAreReported) {
  const std::string path =
      write_file("stoss_scene_test_invalid.json", R"({"format": "stoss-scene/1", "bodies": []})");
  try {
    load_file(path);
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "/bodies: must be a non-empty array, got []\n/time: required");
  }
  fs::remove(path);
}

std::vector<fs::path> example_files() {
  std::vector<fs::path> out;
  for (const auto& entry : fs::directory_iterator(fs::path(STOSS_SOURCE_DIR) / "api" / "examples"))
    if (entry.path().extension() == ".json") out.push_back(entry.path());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(SceneExamples, EveryExampleLoads) {
  const std::vector<fs::path> files = example_files();
  EXPECT_GE(files.size(), 2u);
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.filename().string());
    try {
      const model::Model m = load_file(f.string());
      EXPECT_GT(m.mesh.node_count(), 0);
      EXPECT_GT(m.time.steps(), 0);
    } catch (const SceneError& e) {
      ADD_FAILURE() << e.what();
    }
  }
}

TEST(SceneExamples, TumblingSphereIsTheSeedBallInFreeFlight) {
  // 432 hex8 hollow sphere, no contact, 200 steps of 0.01, a frame every 10 steps: 21 frames; the
  // hard variant takes 40 steps of 0.05: 5 frames. The spin axis (1,2,2)/3 is no cube symmetry axis.
  const std::string dir = std::string(STOSS_SOURCE_DIR) + "/api/examples/";
  const model::Model m = load_file(dir + "tumbling_sphere.json");
  const Summary s = summarize(m);
  EXPECT_EQ(s.effects, (Effects{"inertia", "elasticity"}));
  EXPECT_EQ(s.nodes, 654);
  EXPECT_EQ(s.elements, 432);
  EXPECT_EQ(s.dofs, 3 * 654);
  EXPECT_EQ(s.steps, 200);
  EXPECT_EQ(s.frames, 21);
  EXPECT_EQ(m.time.scheme, model::Scheme::energy_momentum);
  EXPECT_EQ(m.bodies[0].initial_velocity, Eigen::Vector3d(0, 1, -1));
  const Eigen::Vector3d w = m.bodies[0].initial_angular_velocity;
  EXPECT_NEAR(w.norm(), 2, 1e-15);
  EXPECT_NEAR((w.normalized() - Eigen::Vector3d(1, 2, 2) / 3).norm(), 0, 1e-15);
  EXPECT_EQ(*m.bodies[0].center, Eigen::Vector3d(0, 0, 1.3));
  const Summary hard = summarize(load_file(dir + "tumbling_sphere_hard.json"));
  EXPECT_EQ(hard.steps, 40);
  EXPECT_EQ(hard.frames, 5);
}

TEST(SceneSummary, CountsTheLastFrameWhenStepsAreNotAMultiple) {
  json scene = minimal_scene();
  scene["time"] = {{"step", 0.1}, {"end", 1.05}};  // 11 steps
  scene["output"] = {{"every", 5}};
  const Summary s = summarize(load(scene));
  EXPECT_EQ(s.steps, 11);
  EXPECT_EQ(s.frames, 4);  // steps 0, 5, 10, 11
}

// ----------------------------------------------------------------------------------------- schema

/// The schema node at a JSON pointer, following "$ref": "#/$defs/..." links on the way.
const json& resolved(const json& schema, const json& node) {
  if (node.contains("$ref")) {
    const std::string ref = node["$ref"];
    return resolved(schema, schema[json::json_pointer(ref.substr(1))]);
  }
  return node;
}

/// The schema of member `key` of an object whose schema is `node` (descending into oneOf branches).
const json* member_schema(const json& schema, const json& node_in, const std::string& key) {
  const json& node = resolved(schema, node_in);
  if (node.contains("items")) return member_schema(schema, node["items"], key);
  if (node.contains("properties") && node["properties"].contains(key)) return &node["properties"][key];
  if (node.contains("oneOf"))
    for (const json& branch : node["oneOf"])
      if (const json* found = member_schema(schema, branch, key)) return found;
  if (node.contains("additionalProperties") && node["additionalProperties"].is_object())
    return &node["additionalProperties"];
  return nullptr;
}

const json& schema_at(const json& schema, const std::vector<std::string>& path) {
  const json* node = &schema;
  for (const std::string& key : path) {
    node = member_schema(schema, *node, key);
    if (!node) throw std::out_of_range("schema has no " + key);
  }
  return resolved(schema, *node);
}

TEST(SceneSchema, IsDraft202012) {
  const json s = schema();
  EXPECT_EQ(s["$schema"], "https://json-schema.org/draft/2020-12/schema");
  EXPECT_EQ(s["type"], "object");
  EXPECT_EQ(s["additionalProperties"], false);
}

/// The value at `path` of a filled scene, taking the first entry of each list on the way.
const json& filled_value(const json& scene, const std::vector<std::string>& path) {
  const json* value = &scene;
  for (size_t i = 0; i < path.size(); ++i) {
    value = &(*value)[path[i]];
    if (value->is_array() && i + 1 < path.size()) value = &(*value)[0];
  }
  return *value;
}

TEST(SceneSchema, DefaultsAgreeWithTheValidator) {
  // The `default` of each optional field in api/scene.schema.json shall be what load() fills in.
  const json s = schema();
  json rich = with_plate(minimal_scene());
  rich["contact"] = {{{"slave", "ball/outer"}, {"master", "plate/top"}}};
  rich["boundary"] = {{{"surface", "plate/bottom"}}};
  rich["time"]["scheme"] = "hht";
  const json filled_minimal = load(minimal_scene()).scene, filled_rich = load(rich).scene;
  using Path = std::vector<std::string>;
  const std::vector<Path> minimal_paths{{"name"},
                                        {"contact"},
                                        {"boundary"},
                                        {"gravity"},
                                        {"solver"},
                                        {"output"},
                                        {"time", "scheme"},
                                        {"solver", "tolerance"},
                                        {"solver", "max_iterations"},
                                        {"output", "every"},
                                        {"bodies", "material", "model"},
                                        {"bodies", "initial_velocity"},
                                        {"bodies", "initial_angular_velocity"},
                                        {"bodies", "mesh", "hollow_sphere", "center"},
                                        {"bodies", "mesh", "hollow_sphere", "divisions"},
                                        {"bodies", "mesh", "hollow_sphere", "layers"}};
  const std::vector<Path> rich_paths{
      {"time", "alpha"},     {"contact", "enforcement"},       {"contact", "friction"},
      {"contact", "impact"}, {"contact", "switch_hysteresis"}, {"contact", "normal_traction"},
      {"boundary", "fix"}};  // contact/switch_gap: resolved from the surface (test_master_surface.cpp)
  auto expect_default = [&](const json& filled, const Path& path) {
    const std::string where = json(path).dump();
    const json& parent = schema_at(s, Path(path.begin(), path.end() - 1));
    const json* field = member_schema(s, parent, path.back());
    ASSERT_NE(field, nullptr) << where;
    ASSERT_TRUE(field->contains("default")) << where;
    const json& value = filled_value(filled, path);
    if (value.is_object())  // an object default ({}) is filled member by member
      EXPECT_EQ((*field)["default"], json::object()) << where;
    else
      EXPECT_EQ((*field)["default"], value) << where;
  };
  for (const Path& path : minimal_paths) expect_default(filled_minimal, path);
  for (const Path& path : rich_paths) expect_default(filled_rich, path);
}

/// Descends a filled scene and its schema together; every member must be declared.
void expect_declared(const json& schema, const json& node_schema, const json& value,
                     const std::string& where) {
  const json& node = resolved(schema, node_schema);
  if (value.is_object()) {
    for (const auto& [key, member] : value.items()) {
      const json* member_node = member_schema(schema, node, key);
      if (!member_node) {
        ADD_FAILURE() << where << "/" << key << " is not in the schema";
        continue;
      }
      expect_declared(schema, *member_node, member, where + "/" + key);
    }
  } else if (value.is_array() && node.contains("items")) {
    for (size_t i = 0; i < value.size(); ++i)
      expect_declared(schema, node["items"], value[i], where + "/" + std::to_string(i));
  }
}

TEST(SceneSchema, EveryFieldTheValidatorAcceptsIsDeclared) {
  const json s = schema();
  json scene = with_plate(minimal_scene());
  scene["bodies"][0]["center"] = {0, 0, 1.3};
  scene["contact"] = {{{"slave", "ball/outer"},  // frictionless: penalty has no hht form
                       {"master", "plate/top"},
                       {"normal_stiffness", 1},
                       {"tangential_stiffness", 1}}};
  scene["boundary"] = {{{"surface", "plate/bottom"}}};
  scene["time"]["scheme"] = "hht";
  scene["solver"]["ranks"] = 2;  // optional, not filled in: declared all the same
  expect_declared(s, s, load(scene).scene, "");
}

/// Every optional property has a description, and a default unless absence has its own meaning.
void expect_documented(const json& schema, const json& node, const std::string& where) {
  // elements: absent = every element; master_surface, switch_gap: resolved from the master surface
  // (docs/smooth_master_surface.md §1); max_wall_seconds: absent = no limit; checkpoint_every: absent =
  // by checkpoint_seconds.
  const std::set<std::string> without_default{
      "center", "normal_stiffness", "tangential_stiffness", "elements", "master_surface", "switch_gap",
      "max_wall_seconds", "checkpoint_every",
      // adaptive steps and frames at times: optional, or a default
      // relative to time.step and time.end (step/1024, end)
      "tolerance", "min_step", "max_step", "interval",
      // a load: one of pressure and traction; factor 1 without amplitude
      "pressure", "traction", "amplitude"};
  if (node.is_array())
    for (const json& element : node) expect_documented(schema, element, where);
  if (!node.is_object()) return;
  json required = node.value("required", json::array());
  // Members required by one alternative of a oneOf ("file" or "id" of a file mesh) are not optional.
  for (const json& alternative : node.value("oneOf", json::array()))
    for (const json& name : alternative.value("required", json::array())) required.push_back(name);
  for (const auto& [key, child] : node.items()) {
    if (key == "if" || key == "then") continue;  // conditions, not declarations
    if (key != "properties") {
      expect_documented(schema, child, where + "/" + key);
      continue;
    }
    for (const auto& [name, property] : child.items()) {
      expect_documented(schema, property, where + "/" + name);
      if (std::find(required.begin(), required.end(), name) != required.end()) continue;
      EXPECT_TRUE(property.contains("description") || resolved(schema, property).contains("description"))
          << where << "/" << name;
      if (!without_default.contains(name)) {
        EXPECT_TRUE(property.contains("default")) << where << "/" << name;
      }
    }
  }
}

TEST(SceneSchema, OptionalFieldsHaveDefaultAndDescription) {
  const json s = schema();
  expect_documented(s, s, "");
}

}  // namespace
}  // namespace stoss::scene

namespace stoss::scene {
namespace {

/// The worker's path (docs/api.md, GET /v1/jobs/{id}/scene): a scene resolved at POST is built again
/// without validation and gives the same model.
TEST(SceneLoadResolved, BuildsTheSameModelAsLoadFromTheResolvedScene) {
  const model::Model posted =
      load_file(std::string(STOSS_SOURCE_DIR) + "/api/examples/hollow_ball_plate.json");
  const model::Model stored = load_resolved(posted.scene, MeshFiles{});
  EXPECT_EQ(stored.scene, posted.scene);
  EXPECT_EQ(stored.mesh.node_count(), posted.mesh.node_count());
  EXPECT_EQ(stored.effects, posted.effects);
  ASSERT_EQ(stored.contact.size(), 1u);
  EXPECT_EQ(stored.contact[0].master_surface, model::MasterSurface::smooth);
  EXPECT_EQ(stored.contact[0].switch_gap, model::SwitchGap::keep);
  EXPECT_EQ(stored.time.steps(), posted.time.steps());
}

TEST(SceneLoadResolved, DoesNotValidateAgainButAScenePostedRawIsStillValidated) {
  const model::Model posted = load_file(std::string(STOSS_SOURCE_DIR) + "/api/examples/tumbling_bar.json");
  nlohmann::json resolved = posted.scene;
  // A stored scene is trusted: a value validation would refuse (ν ≥ 0.5) reaches the model unchecked.
  resolved["bodies"][0]["material"]["poisson_ratio"] = 0.7;
  EXPECT_DOUBLE_EQ(load_resolved(resolved, MeshFiles{}).bodies[0].material.poisson_ratio, 0.7);
  nlohmann::json raw = resolved;
  raw.erase("solver");  // not resolved (a job an older server stored as posted): validated by load()
  raw["bodies"][0]["material"]["poisson_ratio"] = 0.7;
  EXPECT_THROW(load_resolved(raw, MeshFiles{}), SceneError);
}

}  // namespace
}  // namespace stoss::scene
