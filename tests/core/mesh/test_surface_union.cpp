// Mesh::add_surface_union: several surfaces of one body as one named surface "body/a+b", each face once
// (what a contact side given as a list becomes, docs/scene.md "Contact pairs").
#include <gtest/gtest.h>

#include <stdexcept>

#include "core/mesh/generators.hpp"
#include "core/mesh/mesh.hpp"

namespace stoss::mesh {
namespace {

Mesh two_boxes() {
  Mesh m;
  m.add_body("a", box({0, 0, 0}, {1, 1, 1}, {2, 2, 2}));
  m.add_body("b", box({2, 0, 0}, {3, 1, 1}, {1, 1, 1}));
  return m;
}

TEST(SurfaceUnion, JoinsTheFacesInListOrderOnceEach) {
  Mesh m = two_boxes();
  const std::string name = m.add_surface_union({"a/top", "a/xmax", "a/top"});
  EXPECT_EQ(name, "a/top+xmax+top");
  const std::vector<Quad>& faces = m.surface(name);
  ASSERT_EQ(faces.size(), 8u);
  for (size_t f = 0; f < 4; ++f) EXPECT_EQ(faces[f], m.surface("a/top")[f]);
  for (size_t f = 0; f < 4; ++f) EXPECT_EQ(faces[4 + f], m.surface("a/xmax")[f]);
  EXPECT_EQ(m.surface_nodes(name).size(), 9u + 9u - 3u);
}

TEST(SurfaceUnion, OneNameIsThatSurface) {
  Mesh m = two_boxes();
  EXPECT_EQ(m.add_surface_union({"b/top"}), "b/top");
  EXPECT_FALSE(m.bodies[1].surfaces.contains("top+"));
}

TEST(SurfaceUnion, RefusesSurfacesOfTwoBodiesAndUnknownOnes) {
  Mesh m = two_boxes();
  try {
    m.add_surface_union({"a/top", "b/top"});
    FAIL() << "accepted two bodies";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "surfaces of one union must belong to one body: b/top is not on body 'a'");
  }
  EXPECT_THROW(m.add_surface_union({"a/top", "a/side"}), std::out_of_range);
  EXPECT_THROW(m.add_surface_union({}), std::invalid_argument);
}

}  // namespace
}  // namespace stoss::mesh
