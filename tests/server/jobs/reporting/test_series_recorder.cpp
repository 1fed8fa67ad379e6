// GET /v1/jobs/{id}/series?since=STEP (issue 14): the system shall answer with the rows of the steps after
// STEP only, in JSON (with the step of each row) and CSV, for a succeeded job (from the result file) and a
// running one (from its partial series), so that a client polling with the last step it has gets every step
// exactly once.
#include <gtest/gtest.h>

#include "server/jobs/reporting/series_recorder.hpp"
#include "tests/server/live_server.hpp"

namespace stoss::test {
namespace {

using namespace std::chrono_literals;
using server::jobs::csv_rows_after;
using server::jobs::series_after;

nlohmann::json three_rows() {
  return {{"time", {0.0, 0.1, 0.2}},
          {"total_energy", {1.0, 1.0, 1.0}},
          {"linear_momentum", {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}}},
          {"completed", false},
          {"summary", {{"steps", 2}}}};
}

TEST(SeriesSince, AResultsRowsAreNumberedFromStepZero) {
  const auto all = series_after(three_rows(), std::nullopt);
  EXPECT_EQ(all["step"], nlohmann::json({0, 1, 2}));
  EXPECT_EQ(all["time"].size(), 3u);
}

TEST(SeriesSince, OnlyTheRowsAfterTheStepRemainInEveryRowWiseMember) {
  const auto after = series_after(three_rows(), 0);
  EXPECT_EQ(after["step"], nlohmann::json({1, 2}));
  EXPECT_EQ(after["time"], nlohmann::json({0.1, 0.2}));
  EXPECT_EQ(after["linear_momentum"].size(), 2u);
  EXPECT_EQ(after["summary"]["steps"], 2) << "the summary is not a row-wise member";
  EXPECT_EQ(after["completed"], false);
  const auto none = series_after(three_rows(), 7);
  EXPECT_TRUE(none["step"].empty());
  EXPECT_TRUE(none["total_energy"].empty());
}

TEST(SeriesSince, CsvKeepsItsHeaderAndDropsTheLinesOfStepsUpToSince) {
  const std::string csv = "time,total_energy\n0,1\n0.1,1\n0.2,1\n";
  EXPECT_EQ(csv_rows_after(csv, std::nullopt), csv);
  EXPECT_EQ(csv_rows_after(csv, 0), "time,total_energy\n0.1,1\n0.2,1\n");
  EXPECT_EQ(csv_rows_after(csv, 2), "time,total_energy\n");
  EXPECT_EQ(csv_rows_after(csv, 40), "time,total_energy\n");
}

TEST(SeriesSince, APartialSeriesNamesItsStepsAndIsCutByThem) {
  TempDir dir;
  const auto file = dir.path() / server::jobs::partial_series_file;
  {
    server::jobs::SeriesRecorder recorder(file, 0);
    model::SeriesLayout layout;
    layout.series = {{"total_energy", 1, false}, {"newton_iterations", 1, true}};
    recorder.begin(model::Model{}, layout);
    for (int step = 0; step <= 4; ++step) recorder.step({step, 0.5 * step, {2.0, 3.0 * step}});
  }
  const auto series = server::jobs::read_partial_series(file);
  ASSERT_TRUE(series);
  EXPECT_EQ((*series)["step"], nlohmann::json({0, 1, 2, 3, 4}));
  const auto after = series_after(*series, 2);
  EXPECT_EQ(after["step"], nlohmann::json({3, 4}));
  EXPECT_EQ(after["newton_iterations"], nlohmann::json({9, 12}));
  EXPECT_EQ(after["summary"]["steps"], 4) << "the summary covers every recorded step";
  EXPECT_TRUE(after["summary"]["verdict"].is_null()) << "a run is judged when it ends, not before";
  EXPECT_EQ(after["summary"]["checks"], nlohmann::json::array());
  EXPECT_EQ(server::jobs::partial_series_csv(file, 2),
            "time,total_energy,newton_iterations\n1.5,2,9\n2,2,12\n");
}

// A per-item vector series ([S,k,3], model/series.hpp) in a running job's partial series: its JSON rows are
// k [x, y, z] arrays and its CSV columns name_<i>_x,…, as the result file's routes give them.
TEST(SeriesSince, APartialSeriesGivesItemVectorsInTheTablesTextForms) {
  TempDir dir;
  const auto file = dir.path() / server::jobs::partial_series_file;
  {
    server::jobs::SeriesRecorder recorder(file, 0);
    model::SeriesLayout layout;
    layout.series = {{"total_energy", 1, false}, {"pair_force", 6, false, 2}};
    recorder.begin(model::Model{}, layout);
    for (int step = 0; step <= 2; ++step)
      recorder.step({step, 0.5 * step, {2.0, 1.0 * step, 0, 0, 0, 0, -1.5}});
  }
  const auto series = server::jobs::read_partial_series(file);
  ASSERT_TRUE(series);
  EXPECT_EQ((*series)["pair_force"][2], nlohmann::json({{2.0, 0.0, 0.0}, {0.0, 0.0, -1.5}}));
  EXPECT_EQ(server::jobs::partial_series_csv(file, 1),
            "time,total_energy,pair_force_0_x,pair_force_0_y,pair_force_0_z,pair_force_1_x,pair_force_1_y,"
            "pair_force_1_z\n1,2,2,0,0,0,0,-1.5\n");
}

TEST(SeriesSince, ASucceededJobAnswersWithTheRowsAfterStepInJsonAndCsv) {
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "1"});
  auto c = server.client();
  const std::string id = body_json(submit(c, box_scene(2, 10)))["id"];
  ASSERT_EQ(wait_for_status(c, id, {"succeeded", "failed"})["status"], "succeeded");
  const auto all = body_json(c.Get("/v1/jobs/" + id + "/series"));
  const auto after = body_json(c.Get("/v1/jobs/" + id + "/series?since=4"));
  EXPECT_EQ(after["step"], nlohmann::json({5, 6, 7, 8, 9, 10}));
  ASSERT_EQ(after["kinetic_energy"].size(), 6u);
  EXPECT_EQ(after["kinetic_energy"][0], all["kinetic_energy"][5]);
  EXPECT_EQ(after["linear_momentum"][5], all["linear_momentum"][10]);
  const auto csv = c.Get("/v1/jobs/" + id + "/series?format=csv&since=4");
  ASSERT_EQ(csv->status, 200);
  EXPECT_EQ(std::count(csv->body.begin(), csv->body.end(), '\n'), 7) << "the header and steps 5 to 10";
  EXPECT_EQ(csv->body.rfind("time,kinetic_energy,", 0), 0u);
  EXPECT_TRUE(body_json(c.Get("/v1/jobs/" + id + "/series?since=10"))["time"].empty());
  const auto bad = c.Get("/v1/jobs/" + id + "/series?since=-1");
  EXPECT_EQ(bad->status, 400);
  EXPECT_EQ(body_json(bad)["detail"], "since must be a step number, an integer in [0, 999999999]");
}

TEST(SeriesSince, PollingARunningJobWithItsLastStepGetsEveryStepOnce) {
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "1"});
  auto c = server.client();
  const std::string id = body_json(submit(c, box_scene(4, 100'000, {1, 0, 0}, 2.0)))["id"];
  std::vector<long long> steps;
  int polls_with_rows = 0;
  ASSERT_TRUE(eventually(
      [&] {
        const std::string since = steps.empty() ? "" : "?since=" + std::to_string(steps.back());
        auto r = c.Get("/v1/jobs/" + id + "/series" + since);
        if (!r || r->status != 200) return false;
        const auto chunk = nlohmann::json::parse(r->body);
        EXPECT_EQ(chunk["completed"], false);
        EXPECT_TRUE(chunk["summary"]["verdict"].is_null()) << "no verdict while the run goes on";
        EXPECT_EQ(chunk["summary"]["checks"], nlohmann::json::array());
        EXPECT_EQ(chunk["step"].size(), chunk["total_energy"].size());
        for (const auto& step : chunk["step"]) steps.push_back(step.get<long long>());
        polls_with_rows += chunk["step"].empty() ? 0 : 1;
        return polls_with_rows >= 3;
      },
      120s));
  EXPECT_EQ(c.Post("/v1/jobs/" + id + "/cancel")->status, 202);
  for (std::size_t i = 0; i < steps.size(); ++i)
    ASSERT_EQ(steps[i], static_cast<long long>(i)) << "step " << i;
  const nlohmann::json job = wait_for_status(c, id, {"canceled", "failed", "succeeded"}, 60s);
  // Once ended, the partial summary carries the job's own verdict and checks (a canceled run is judged too).
  ASSERT_TRUE(job["summary"].is_object()) << job.dump();
  ASSERT_TRUE(job["summary"]["verdict"] == "ok" || job["summary"]["verdict"] == "suspect") << job.dump();
  const auto ended = nlohmann::json::parse(c.Get("/v1/jobs/" + id + "/series?since=999999999")->body);
  EXPECT_EQ(ended["summary"]["verdict"], job["summary"]["verdict"]);
  EXPECT_EQ(ended["summary"]["checks"], job["summary"]["checks"]);
  EXPECT_FALSE(ended["summary"]["checks"].empty());
}

}  // namespace
}  // namespace stoss::test
