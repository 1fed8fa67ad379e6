// The study shall measure error against a fine reference: second-order schemes show error ratios of
// about 4 when h halves, and every row carries the cost (wall time, Newton iterations).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/mesh/generators.hpp"
#include "core/study/study.hpp"

namespace stoss::study {
namespace {

model::Model spinning_bar() {
  model::Model m;
  mesh::BodyMesh bar = mesh::box({0, 0, 0}, {2, 1, 1}, {2, 1, 1});
  m.mesh.add_body("bar", bar);
  model::BodySpec b;
  b.name = "bar";
  b.material = {"saint_venant_kirchhoff", 100, 0.3, 1};
  b.initial_angular_velocity = {0.5, 1, 2};
  m.bodies.push_back(b);
  m.time = {model::Scheme::energy_momentum, 0.04, 0.8};
  m.solver.tolerance = 1e-12;
  m.effects = model::resolve_effects(m);
  return m;
}

TEST(Study, ErrorsFallAtSecondOrderAndCostsAreRecorded) {
  Options o;
  o.steps = {0.01, 0.005, 0.0025};  // asymptotic range: the stiffest mode has hω ≤ 0.35
  o.repeat = 1;
  const Result r = run(spinning_bar(), o);
  ASSERT_EQ(r.rows.size(), 9u);
  EXPECT_DOUBLE_EQ(r.reference_step, 0.0025 / 32);
  for (size_t s = 0; s < 3; ++s) {
    const Row &coarse = r.rows[3 * s], &mid = r.rows[3 * s + 1], &fine = r.rows[3 * s + 2];
    ASSERT_TRUE(coarse.completed && mid.completed && fine.completed) << coarse.scheme;
    const double ratio = mid.displacement_error / fine.displacement_error;
    EXPECT_GT(ratio, 3.0) << coarse.scheme << ": second order means a ratio near 4";
    EXPECT_LT(ratio, 5.5) << coarse.scheme;
    EXPECT_GT(coarse.displacement_error, mid.displacement_error);
    EXPECT_GT(fine.wall_seconds, 0);
    EXPECT_EQ(fine.steps, 320);
    EXPECT_GE(fine.newton_iterations, fine.steps);
  }
  EXPECT_EQ(r.rows[0].scheme, "energy_momentum");
  EXPECT_LT(r.rows[0].energy_error, 1e-9) << "energy_momentum conserves energy at every h";
  EXPECT_GT(r.rows[3].energy_error, 1e3 * r.rows[0].energy_error) << "midpoint does not";
}

// Tolerances beside steps (issue 22 §2): each scheme once per time.tolerance, first step the scene's; a
// tighter tolerance takes more steps for a smaller error, each within 10 × its tolerance; the tables carry
// the tolerance (JSON, CSV column, Markdown "TOL").
TEST(Study, TolerancesAreSweptBesideStepsAndTheirRowsSayWhichTheyAre) {
  Options o;
  o.schemes = {model::Scheme::energy_momentum};
  o.steps = {0.02};
  o.tolerances = {1e-3, 1e-4};
  o.reference_step = 0.02 / 64;
  o.repeat = 1;
  model::Model m = spinning_bar();
  m.time.step = 0.005;  // the first step: midpoint-type schemes accept it without an estimate (§2.7)
  const Result r = run(m, o);
  ASSERT_EQ(r.rows.size(), 3u);
  EXPECT_EQ(r.rows[0].tolerance, 0);
  const Row &loose = r.rows[1], &tight = r.rows[2];
  ASSERT_TRUE(loose.completed && tight.completed) << loose.failure << tight.failure;
  EXPECT_EQ(loose.tolerance, 1e-3);
  EXPECT_EQ(loose.step, 0.005) << "the first step is the scene's time.step";
  EXPECT_GT(tight.steps, loose.steps);
  EXPECT_LT(tight.displacement_error, loose.displacement_error);
  EXPECT_LE(loose.displacement_error, 10 * 1e-3);
  EXPECT_LE(tight.displacement_error, 10 * 1e-4);
  EXPECT_LT(tight.energy_error, 1e-9) << "energy–momentum with varying steps";
  EXPECT_EQ(result_from_json(to_json(r)).rows[2].tolerance, 1e-4);
  const std::string csv = to_csv(r);
  EXPECT_NE(csv.find("newton_per_step,tolerance\n"), std::string::npos) << csv;
  EXPECT_NE(to_markdown(r).find("| energy_momentum | TOL 0.0001 ("), std::string::npos) << to_markdown(r);
  std::printf("spinning bar: TOL 1e-3 %d steps error %.2e; TOL 1e-4 %d steps error %.2e\n", loose.steps,
              loose.displacement_error, tight.steps, tight.displacement_error);
}

TEST(Study, EachPointRunsRepeatTimesAndShowsTheMedianWallTime) {
  Options o;
  o.schemes = {model::Scheme::energy_momentum, model::Scheme::midpoint};
  o.steps = {0.08};
  o.repeat = 3;
  std::vector<std::pair<study::Run, double>> finished;
  o.run_finished = [&](const study::Run& run, const model::Summary& s, const std::string&) {
    finished.push_back({run, s.wall_seconds});
  };
  EXPECT_EQ(plan(spinning_bar(), o).size(), 7u);  // the reference once, each point 3 times
  const Result r = run(spinning_bar(), o);
  ASSERT_EQ(finished.size(), 7u);
  ASSERT_EQ(r.rows.size(), 2u);
  EXPECT_EQ(r.repeat, 3);
  for (size_t k = 0; k < 2; ++k) {
    std::vector<double> walls;
    for (size_t i = 1 + 3 * k; i < 4 + 3 * k; ++i) {
      EXPECT_EQ(finished[i].first.repetition, static_cast<int>(i - 1 - 3 * k));
      walls.push_back(finished[i].second);
    }
    // The row keeps the three timings in run order, and shows their median.
    EXPECT_EQ(r.rows[k].wall_seconds_runs, walls) << r.rows[k].scheme;
    std::sort(walls.begin(), walls.end());
    EXPECT_EQ(r.rows[k].wall_seconds, walls[1]) << r.rows[k].scheme;
    EXPECT_GT(walls[0], 0) << "each run is timed";
  }
  const nlohmann::json table = to_json(r);
  ASSERT_EQ(table["rows"][1]["wall_seconds_runs"].size(), 3u) << table.dump();
  EXPECT_EQ(table["rows"][1]["wall_seconds_runs"].get<std::vector<double>>(), r.rows[1].wall_seconds_runs);
  EXPECT_EQ(result_from_json(table).rows[1].wall_seconds_runs, r.rows[1].wall_seconds_runs);
  EXPECT_TRUE(result_from_json(nlohmann::json{{"rows", {{{"scheme", "hht"}, {"wall_seconds", 1.5}}}}})
                  .rows[0]
                  .wall_seconds_runs.empty())
      << "a table from before the runs were kept reads with the median alone";
  EXPECT_EQ(to_json(r)["timing"], "wall seconds: the median of 3 runs");
  EXPECT_EQ(to_markdown(r).rfind("wall seconds: the median of 3 runs of each scheme and step\n", 0), 0u);
}

// The momenta of a body under gravity change by its impulse: no momentum_error there (issue 25 §3),
// while the free bar's is reported (docs/results.md "Verdict").
TEST(Study, MomentumErrorOnlyWhereTheSystemIsFree) {
  Options o;
  o.schemes = {model::Scheme::energy_momentum};
  o.steps = {0.08};
  o.repeat = 1;
  const Result free = run(spinning_bar(), o);
  ASSERT_EQ(free.rows.size(), 1u);
  EXPECT_TRUE(std::isfinite(free.rows[0].momentum_error));
  EXPECT_LT(free.rows[0].momentum_error, 1e-8);
  model::Model falling = spinning_bar();
  falling.gravity = Eigen::Vector3d(0, 0, -9.81);
  falling.effects = model::resolve_effects(falling);
  const Result held = run(falling, o);
  ASSERT_EQ(held.rows.size(), 1u);
  EXPECT_TRUE(std::isnan(held.rows[0].momentum_error));
  EXPECT_NE(to_json(held).dump().find("\"momentum_error\":null"), std::string::npos) << to_json(held).dump();
}

TEST(Study, TableFormatsListEveryRow) {
  Options o;
  o.schemes = {model::Scheme::energy_momentum};
  o.steps = {0.08, 0.04};
  const Result r = run(spinning_bar(), o);
  const std::string csv = to_csv(r);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3) << csv;
  EXPECT_EQ(csv.rfind("scheme,step,steps,completed,displacement_error", 0), 0u) << csv;
  EXPECT_EQ(to_json(r)["rows"].size(), 2u);
  EXPECT_NE(to_markdown(r).find("| energy_momentum | 0.04 |"), std::string::npos) << to_markdown(r);
}

TEST(Study, NoStepSizesIsAnError) {
  EXPECT_THROW(run(spinning_bar(), Options{}), std::invalid_argument);
}

}  // namespace
}  // namespace stoss::study
