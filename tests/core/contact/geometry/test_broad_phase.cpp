// The broad phase shall return exactly the master faces whose boxes overlap a slave node's box
// (docs/theory.md §3.4), without an all-pairs loop, and keep its lists local as the mesh grows.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

#include "core/contact/geometry/broad_phase.hpp"
#include "core/mesh/generators.hpp"

namespace stoss::contact {
namespace {

std::vector<Box> random_boxes(std::mt19937& rng, int n, double spread, double size) {
  std::uniform_real_distribution<double> at(-spread, spread), extent(0.0, size);
  std::vector<Box> boxes;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d lo(at(rng), at(rng), at(rng));
    boxes.emplace_back(lo, lo + Eigen::Vector3d(extent(rng), extent(rng), extent(rng)));
  }
  return boxes;
}

std::vector<int> brute_force(const std::vector<Box>& boxes, const Box& q) {
  std::vector<int> out;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i)
    if (boxes[i].intersects(q)) out.push_back(i);
  return out;
}

class BoxGridQuery : public ::testing::TestWithParam<std::tuple<unsigned, double>> {};

TEST_P(BoxGridQuery, FindsExactlyTheOverlappingBoxes) {
  const auto [seed, cell] = GetParam();
  std::mt19937 rng(seed);
  const std::vector<Box> boxes = random_boxes(rng, 300, 5.0, 1.0);
  const BoxGrid grid(boxes, cell);
  std::vector<int> found;
  for (const Box& q : random_boxes(rng, 200, 6.0, 0.8)) {
    grid.query(q, found);
    EXPECT_EQ(found, brute_force(boxes, q));
  }
}

INSTANTIATE_TEST_SUITE_P(SeedsAndCells, BoxGridQuery,
                         ::testing::Combine(::testing::Values(1u, 2u, 3u),
                                            ::testing::Values(1e-3, 0.5, 1.0, 50.0)));

TEST(BoxGrid, EmptyGridAndFarQueriesFindNothing) {
  std::vector<int> found{7};
  BoxGrid().query(Box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()), found);
  EXPECT_TRUE(found.empty());
  const BoxGrid grid({Box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones())}, 0.5);
  grid.query(Box(Eigen::Vector3d::Constant(5), Eigen::Vector3d::Constant(6)), found);
  EXPECT_TRUE(found.empty());
}

// A diverging run hands the search boxes 1e300 wide or not finite at all (found by the fuzz test: a
// velocity of 1e300 crashed the grid's int cell count); the grid still answers, and a box it holds
// overlaps the query it should.
TEST(BoxGrid, HugeAndNonFiniteBoxesStillGiveAGridThatAnswers) {
  const Box unit(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  for (const Box& wild : {Box(Eigen::Vector3d::Zero(), Eigen::Vector3d(1e300, 1, 1)),
                          Box(Eigen::Vector3d::Zero(), Eigen::Vector3d(inf, 1, 1)),
                          Box(Eigen::Vector3d(nan, 0, 0), Eigen::Vector3d(1, 1, 1))}) {
    const BoxGrid grid({unit, wild}, 0.25);
    std::vector<int> found;
    grid.query(Box(Eigen::Vector3d::Constant(0.4), Eigen::Vector3d::Constant(0.6)), found);
    EXPECT_NE(std::find(found.begin(), found.end(), 0), found.end()) << wild.max().transpose();
  }
}

/// A cube of side 1 (n × n × 1 cells) above a plate of n × n top faces, gap `gap`.
mesh::Mesh block_on_plate(int n, double gap) {
  mesh::Mesh m;
  m.add_body("plate", mesh::box({0, 0, -0.2}, {1, 1, 0}, {n, n, 1}));
  m.add_body("block", mesh::box({0, 0, gap}, {1, 1, gap + 0.5}, {n, n, 1}));
  return m;
}

TEST(BroadPhase, CandidatesAreTheFacesUnderEachSlaveNode) {
  const mesh::Mesh m = block_on_plate(8, 0.01);
  const PairSurfaces s = pair_surfaces(m, "block/bottom", "plate/top");
  const Eigen::VectorXd x = m.reference_positions();
  BroadPhase broad;
  broad.update(s, x, x);  // at rest: boxes inflated by half a face size only
  ASSERT_EQ(broad.near_slaves().size(), s.slave_nodes.size());
  for (size_t i = 0; i < s.slave_nodes.size(); ++i) {
    const Eigen::Vector3d p = x.segment<3>(3 * s.slave_nodes[i]);
    for (size_t f = 0; f < s.faces.size(); ++f) {
      Box face;
      for (int I : s.faces[f]) face.extend(m.nodes[I]);
      const bool under = face.exteriorDistance(p) < 1e-12 + 0.01;
      const auto c = broad.candidates(static_cast<int>(i));
      const bool listed = std::find(c.begin(), c.end(), static_cast<int>(f)) != c.end();
      if (under) {
        EXPECT_TRUE(listed) << "slave " << i << " misses the face " << f << " right below it";
      }
    }
    EXPECT_LE(broad.candidates(static_cast<int>(i)).size(), 16u) << "lists stay local";
  }
}

TEST(BroadPhase, FarBodiesHaveNoCandidatesAndMotionWidensTheSearch) {
  const mesh::Mesh m = block_on_plate(4, 2.0);
  const PairSurfaces s = pair_surfaces(m, "block/bottom", "plate/top");
  const Eigen::VectorXd x = m.reference_positions();
  BroadPhase broad;
  broad.update(s, x, x);
  EXPECT_TRUE(broad.near_slaves().empty());
  Eigen::VectorXd falling = x;  // the block falls 2.1 within the step: now it may hit the plate
  for (int I = m.bodies[1].node_begin; I < m.bodies[1].node_end; ++I) falling[3 * I + 2] -= 2.1;
  broad.update(s, x, falling);
  EXPECT_EQ(broad.near_slaves().size(), s.slave_nodes.size());
}

TEST(BroadPhase, RefreshRequeriesOnlyNodesThatLeftTheirBoxes) {
  const mesh::Mesh m = block_on_plate(4, 2.0);
  const PairSurfaces s = pair_surfaces(m, "block/bottom", "plate/top");
  const Eigen::VectorXd x = m.reference_positions();
  BroadPhase broad;
  broad.update(s, x, x);
  EXPECT_EQ(broad.refresh(s, x), 0) << "nothing moved";
  Eigen::VectorXd moved = x;
  const int node = s.slave_nodes[0];
  moved[3 * node + 2] = 0.001;  // one slave node jumps down onto the plate
  EXPECT_EQ(broad.refresh(s, moved), 1);
  EXPECT_EQ(broad.near_slaves(), std::vector<int>{0});
  EXPECT_FALSE(broad.candidates(0).empty());
}

TEST(BroadPhase, ListsStayLocalAsTheMeshGrows) {
  // O(n): the candidates per slave node do not grow with the number of faces.
  for (int n : {4, 16, 64}) {
    const mesh::Mesh m = block_on_plate(n, 0.0);
    const PairSurfaces s = pair_surfaces(m, "block/bottom", "plate/top");
    const Eigen::VectorXd x = m.reference_positions();
    BroadPhase broad;
    broad.update(s, x, x);
    size_t total = 0;
    for (int i : broad.near_slaves()) total += broad.candidates(i).size();
    EXPECT_LE(double(total) / s.slave_nodes.size(), 16.0) << n << " × " << n << " faces";
  }
}

TEST(PairSurfaces, TributaryAreasAddUpToTheSlaveSurface) {
  const mesh::Mesh m = block_on_plate(4, 0.01);
  const PairSurfaces s = pair_surfaces(m, "block/bottom", "plate/top");
  double area = 0;
  for (double a : s.tributary_area) area += a;
  EXPECT_NEAR(area, 1.0, 1e-14);
  EXPECT_EQ(s.slave_nodes.size(), 25u);
  EXPECT_EQ(s.faces.size(), 16u);
  EXPECT_NEAR(s.mean_face_size, 0.25, 1e-15);
  EXPECT_THROW(pair_surfaces(m, "block/nothing", "plate/top"), std::out_of_range);
}

}  // namespace
}  // namespace stoss::contact
