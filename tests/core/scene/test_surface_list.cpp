// A contact side may be a list of surfaces of one body, used as one surface (their union, each face once):
// "master": ["box/top", "box/xmax"]. Each name must exist (pointer of the list element), the surfaces of
// one list belong to one body, none repeats. A master union that forms a manifold quad surface carries a
// smooth master surface across the edges its surfaces share (docs/scene.md, "Contact").
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/scene/scene.hpp"
#include "tests/core/scene/scene_issues.hpp"

namespace stoss::scene {
namespace {

using nlohmann::json;

const json material = {{"youngs_modulus", 1e4}, {"poisson_ratio", 0.4}, {"density", 1}};

/// A small block above a 4×4×2 box; pair 0 has the given master.
json block_on_box(const json& master) {
  return {
      {"format", "stoss-scene/1"},
      {"bodies",
       {{{"name", "box"},
         {"mesh", {{"box", {{"min", {0, 0, 0}}, {"max", {4, 4, 2}}, {"divisions", {4, 4, 2}}}}}},
         {"material", material}},
        {{"name", "block"},
         {"mesh", {{"box", {{"min", {3.6, 1.5, 2.1}}, {"max", {4.4, 2.5, 2.6}}, {"divisions", {2, 2, 1}}}}}},
         {"material", material}}}},
      {"contact", {{{"slave", "block/bottom"}, {"master", master}}}},
      {"time", {{"step", 0.01}, {"end", 0.1}}}};
}

using testing::issues_of;

std::set<std::array<int, 4>> sorted_faces(const std::vector<mesh::Quad>& faces) {
  std::set<std::array<int, 4>> out;
  for (mesh::Quad q : faces) {
    std::sort(q.begin(), q.end());
    out.insert(q);
  }
  return out;
}

TEST(SurfaceList, TopAndXmaxAreOneSmoothMasterWithEveryFaceOnce) {
  const model::Model m = load(block_on_box({"box/top", "box/xmax"}));
  const model::ContactPair& pair = m.contact.at(0);
  EXPECT_EQ(pair.master, "box/top+xmax");
  EXPECT_EQ(pair.master_surface, model::MasterSurface::smooth);
  EXPECT_EQ(m.mesh.surface(pair.master).size(), 16u + 8u);
  EXPECT_EQ(m.scene["contact"][0]["master"], json({"box/top", "box/xmax"}))
      << "the resolved scene keeps the list";
}

TEST(SurfaceList, AFaceNamedTwiceIsCountedOnce) {
  const model::Model m = load(block_on_box({"box/top", "box/boundary"}));
  EXPECT_EQ(m.mesh.surface(m.contact.at(0).master).size(), m.mesh.surface("box/boundary").size());
  EXPECT_EQ(sorted_faces(m.mesh.surface(m.contact.at(0).master)),
            sorted_faces(m.mesh.surface("box/boundary")));
}

TEST(SurfaceList, BoundaryIsTheListOfAllSixSides) {
  const model::Model all =
      load(block_on_box({"box/xmin", "box/xmax", "box/ymin", "box/ymax", "box/bottom", "box/top"}));
  const model::Model boundary = load(block_on_box("box/boundary"));
  EXPECT_EQ(sorted_faces(all.mesh.surface(all.contact.at(0).master)),
            sorted_faces(boundary.mesh.surface("box/boundary")));
  EXPECT_EQ(boundary.mesh.surface("box/boundary").size(), 2u * (16 + 8 + 8));
  EXPECT_EQ(all.contact.at(0).master_surface, model::MasterSurface::smooth);
  EXPECT_EQ(boundary.contact.at(0).master_surface, model::MasterSurface::smooth);
}

TEST(SurfaceList, ASingleElementListIsThatSurface) {
  const model::Model m = load(block_on_box({"box/top"}));
  EXPECT_EQ(m.contact.at(0).master, "box/top");
}

TEST(SurfaceList, ASlaveListIsTheUnionOfItsNodes) {
  json scene = block_on_box("box/top");
  scene["contact"][0]["slave"] = {"block/bottom", "block/xmin"};
  const model::Model m = load(scene);
  EXPECT_EQ(m.contact.at(0).slave, "block/bottom+xmin");
  EXPECT_EQ(m.mesh.surface_nodes(m.contact.at(0).slave).size(), 9u + 6u - 3u);
}

TEST(SurfaceList, AnUnknownSurfaceIsNamedByItsListElement) {
  const auto issues = issues_of(block_on_box({"box/top", "box/side"}));
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].pointer, "/contact/0/master/1");
  EXPECT_EQ(issues[0].message.rfind("body \"box\" has no surface \"side\" (it has ", 0), 0u)
      << issues[0].message;
}

TEST(SurfaceList, SurfacesOfTwoBodiesAreRefused) {
  const auto issues = issues_of(block_on_box({"box/top", "block/top"}));
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].pointer, "/contact/0/master/1");
  EXPECT_EQ(issues[0].message,
            "must be a surface of body \"box\" like /contact/0/master/0 (the surfaces of one list belong to "
            "one body), "
            "got \"block/top\"");
}

TEST(SurfaceList, ARepeatedSurfaceIsRefused) {
  const auto issues = issues_of(block_on_box({"box/top", "box/xmax", "box/top"}));
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].pointer, "/contact/0/master/2");
  EXPECT_EQ(issues[0].message, "must not repeat a surface, got \"box/top\" (also /contact/0/master/0)");
}

TEST(SurfaceList, AnEmptyListOrANonStringIsRefused) {
  auto issues = issues_of(block_on_box(json::array()));
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].pointer, "/contact/0/master");
  EXPECT_NE(issues[0].message.find("non-empty array"), std::string::npos) << issues[0].message;
  issues = issues_of(block_on_box({"box/top", 3}));
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].pointer, "/contact/0/master/1");
}

TEST(SurfaceList, AListOnTheSlavesBodyIsRefused) {
  json scene = block_on_box({"block/top", "block/xmax"});
  const auto issues = issues_of(scene);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].pointer, "/contact/0/master");
  EXPECT_EQ(issues[0].message.rfind("must be on another body than slave", 0), 0u) << issues[0].message;
}

TEST(SurfaceList, AStoredResolvedSceneBuildsTheSameUnion) {
  const model::Model first = load(block_on_box({"box/top", "box/xmax"}));
  const model::Model again = load_resolved(first.scene, {});
  EXPECT_EQ(again.contact.at(0).master, "box/top+xmax");
  EXPECT_EQ(again.mesh.surface("box/top+xmax"), first.mesh.surface("box/top+xmax"));
  EXPECT_EQ(again.contact.at(0).master_surface, model::MasterSurface::smooth);
}

}  // namespace
}  // namespace stoss::scene
