// A pair's contact_area (issue 23 §4, docs/results.md series/contact_area) shall count the tributary areas
// of the slave nodes in contact that carry a force: a node kept active with a tensile multiplier (§3.5's
// anti-cycling) reports pressure 0 and adds no area; the pressures are each node's force over its area.
#include <gtest/gtest.h>

#include "core/contact/contact_term.hpp"
#include "core/mesh/generators.hpp"

namespace stoss::contact {
namespace {

/// A ContactTerm that records the forces it is given, as an enforcement's end_step does.
class RecordedPair final : public ContactTerm {
 public:
  using ContactTerm::ContactTerm;
  void register_pair_blocks(solve::BlockPattern&) override {}
  void add_pair(const time::StepContext&, const Eigen::VectorXd&, Eigen::VectorXd&,
                solve::BlockPattern*) const override {}
  void record(const std::vector<std::pair<int, double>>& forces) {
    clear_pressure();
    for (const auto& [slave, force] : forces) add_pressure(slave, force);
  }
};

TEST(ContactArea, CountsOnlyTheSlaveNodesThatCarryAForce) {
  mesh::Mesh mesh;
  mesh.add_body("lower", mesh::box({0, 0, 0}, {1, 1, 0.5}, {3, 3, 1}));
  mesh.add_body("upper", mesh::box({0, 0, 0.5}, {1, 1, 1}, {2, 2, 1}));
  model::ContactPair pair;
  pair.slave = "upper/bottom";
  pair.master = "lower/top";
  RecordedPair term(mesh, pair);
  const std::vector<double>& area = term.surfaces().tributary_area;
  ASSERT_EQ(area.size(), 9u);
  term.record({{0, 2.0}, {4, 0.0}, {8, 3.0}});  // node 4 active, its multiplier tensile: force 0
  EXPECT_DOUBLE_EQ(term.report().contact_area, area[0] + area[8]);
  Eigen::VectorXd p = Eigen::VectorXd::Constant(mesh.node_count(), -1);
  term.contact_pressure(p);
  const std::vector<int>& nodes = term.surfaces().slave_nodes;
  EXPECT_DOUBLE_EQ(p[nodes[0]], 2.0 / area[0]);
  EXPECT_EQ(p[nodes[4]], 0.0) << "the tensile node's pressure is 0";
  EXPECT_DOUBLE_EQ(p[nodes[8]], 3.0 / area[8]);
  EXPECT_EQ(p[nodes[1]], -1) << "a node not in contact is left alone";
  term.record({{4, 1.0}});
  EXPECT_DOUBLE_EQ(term.report().contact_area, area[4]) << "the next step starts from none";
}

}  // namespace
}  // namespace stoss::contact
