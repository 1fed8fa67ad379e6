// Study jobs against the live service: the system shall run a sweep of schemes × step sizes on the user's
// scene as a job (POST /v1/studies) and serve its table as JSON, CSV and Markdown.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/server/live_server.hpp"

namespace stoss::test {
namespace {

using namespace std::chrono_literals;

/// One hex8 element spinning about z at 2 rad/s, end time 0.2.
nlohmann::json spinning_cube() {
  return box_scene(1, 20, {0, 0, 0}, 2.0);
}

std::string created_id(const httplib::Result& r) {
  EXPECT_TRUE(r);
  if (!r) return "";
  EXPECT_EQ(r->status, 201) << r->body;
  return nlohmann::json::parse(r->body).value("id", "");
}

/// The row of `table` for `scheme` and `step`.
nlohmann::json row(const nlohmann::json& table, const std::string& scheme, double step) {
  for (const auto& r : table["rows"])
    if (r["scheme"] == scheme && r["step"].get<double>() == step) return r;
  ADD_FAILURE() << "no row " << scheme << " h = " << step << " in " << table.dump();
  return nlohmann::json::object();
}

/// The system shall queue a study as a job of kind "study", count its progress in runs, and link its table.
TEST(Study, RunsTheSweepAsAJobAndServesTheTable) {
  TempDir dir;
  LiveServer server(dir.path() / "data");
  auto c = server.client();
  auto r = submit_study(c, study_body(spinning_cube(), {0.04, 0.02}, {"energy_momentum", "midpoint"}));
  const std::string id = created_id(r);
  ASSERT_FALSE(id.empty());
  EXPECT_EQ(r->get_header_value("Location"), "/v1/jobs/" + id);
  const auto queued = nlohmann::json::parse(r->body);
  EXPECT_EQ(queued["kind"], "study");
  EXPECT_EQ(queued["progress"]["steps"], 13);  // the reference and 2 schemes × 2 steps, 3 times each (repeat)
  EXPECT_DOUBLE_EQ(queued["study"]["reference_step"].get<double>(), 0.02 / 32);

  const auto done = wait_for_status(c, id, {"succeeded", "failed", "canceled"});
  ASSERT_EQ(done["status"], "succeeded") << done.dump();
  EXPECT_EQ(done["progress"]["step"], 13);
  EXPECT_EQ(done["links"]["study"], "/v1/jobs/" + id + "/study");
  EXPECT_FALSE(done["links"].contains("result"));
  EXPECT_EQ(done["summary"]["runs_done"], 13);
  EXPECT_TRUE(done["summary"]["completed"].get<bool>());

  const auto table = body_json(c.Get("/v1/jobs/" + id + "/study"));
  ASSERT_EQ(table["rows"].size(), 4u) << table.dump();
  for (const auto& each : table["rows"]) {
    EXPECT_TRUE(each["completed"].get<bool>()) << each.dump();
    EXPECT_GT(each["wall_seconds"].get<double>(), 0.0) << each.dump();
  }
  for (double h : {0.04, 0.02})
    EXPECT_LT(row(table, "energy_momentum", h)["energy_error"].get<double>(), 1e-9);
  for (const std::string scheme : {"energy_momentum", "midpoint"})
    EXPECT_LT(row(table, scheme, 0.02)["displacement_error"].get<double>(),
              row(table, scheme, 0.04)["displacement_error"].get<double>())
        << scheme;
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "data/jobs" / id / "attempt-1/study.json"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "data/jobs" / id / "attempt-1/study.json.partial"));
}

/// The system shall serve the table as CSV and Markdown, and refuse a result file for a study.
TEST(Study, ServesCsvAndMarkdownAndNoResultFile) {
  TempDir dir;
  LiveServer server(dir.path() / "data");
  auto c = server.client();
  const std::string id =
      created_id(submit_study(c, study_body(spinning_cube(), {0.04, 0.02}, {"energy_momentum", "midpoint"})));
  ASSERT_EQ(wait_for_status(c, id, {"succeeded", "failed", "canceled"})["status"], "succeeded");

  auto csv = c.Get("/v1/jobs/" + id + "/study?format=csv");
  ASSERT_EQ(csv->status, 200);
  EXPECT_EQ(csv->get_header_value("Content-Type"), "text/csv");
  EXPECT_EQ(csv->body.substr(0, csv->body.find('\n')),
            "scheme,step,steps,completed,displacement_error,energy_error,momentum_error,wall_seconds,"
            "newton_iterations,newton_per_step");
  EXPECT_EQ(std::count(csv->body.begin(), csv->body.end(), '\n'), 5);  // a header and 4 rows
  auto markdown = c.Get("/v1/jobs/" + id + "/study?format=markdown");
  ASSERT_EQ(markdown->status, 200);
  EXPECT_NE(markdown->body.find("| midpoint | 0.02 |"), std::string::npos) << markdown->body;
  EXPECT_EQ(c.Get("/v1/jobs/" + id + "/study?format=xml")->status, 400);

  for (const std::string suffix : {"/result", "/result.xdmf", "/series"}) {
    auto r = c.Get("/v1/jobs/" + id + suffix);
    EXPECT_EQ(r->status, 409) << suffix;
    EXPECT_NE(r->body.find("a study job has no result file; see /v1/jobs/" + id + "/study"),
              std::string::npos)
        << r->body;
  }
  const std::string log = c.Get("/v1/jobs/" + id + "/log")->body;
  EXPECT_NE(log.find("run 1/13: reference energy_momentum"), std::string::npos) << log;
  EXPECT_NE(log.find("study completed: 13 runs"), std::string::npos) << log;
}

/// The system shall stop a running study when canceled (within the run in progress) and serve no table.
TEST(Study, CancelsARunningStudy) {
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "1"});
  auto c = server.client();
  // 4³ elements to t = 10: the reference run alone is 32 000 steps of h = 0.01 / 32.
  const std::string id = created_id(submit_study(c, study_body(box_scene(4, 1000, {1, 0, 0}, 2.0), {0.01})));
  ASSERT_TRUE(eventually([&] { return job(c, id)["status"] == "running"; }, 60s));
  auto cancel = c.Post("/v1/jobs/" + id + "/cancel");
  ASSERT_EQ(cancel->status, 202);
  const auto stopped = wait_for_status(c, id, {"canceled", "succeeded", "failed"}, 60s);
  ASSERT_EQ(stopped["status"], "canceled") << stopped.dump();
  EXPECT_FALSE(stopped["summary"]["completed"].get<bool>());
  EXPECT_LT(stopped["summary"]["runs_done"].get<int>(), 4);
  EXPECT_EQ(c.Get("/v1/jobs/" + id + "/study")->status, 409);
  EXPECT_NE(c.Get("/v1/jobs/" + id + "/log")->body.find("canceled after"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "data/jobs" / id / "attempt-1/study.json"));
}

}  // namespace
}  // namespace stoss::test
