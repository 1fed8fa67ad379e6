// A study job in isolation: the system shall run the sweep of core/study, report progress as runs done of
// runs total, stop when canceled, and read its table back exactly as written.
#include <gtest/gtest.h>

#include <sstream>

#include "core/scene/scene.hpp"
#include "server/jobs/running/study_job.hpp"
#include "tests/server/live_server.hpp"

namespace stoss::server::jobs {
namespace {

study::Options sweep() {
  study::Options o;
  o.schemes = {model::Scheme::energy_momentum, model::Scheme::midpoint};
  o.steps = {0.04, 0.02};
  o.reference_step = 0.02 / 32;
  o.repeat = 1;
  return o;
}

Job study_job(const study::Options& options) {
  Job job;
  job.kind = Kind::study;
  job.study = study_params_json(options);
  return job;
}

TEST(StudyJob, ParametersRoundTripThroughTheirJson) {
  const study::Options o = study_options(study_params_json(sweep()));
  EXPECT_EQ(o.steps, sweep().steps);
  EXPECT_EQ(o.schemes, sweep().schemes);
  EXPECT_EQ(o.reference_step, sweep().reference_step);
  EXPECT_EQ(o.repeat, 1);
  EXPECT_EQ(study_run_count(o), 5);
  study::Options thrice = sweep();
  thrice.repeat = 3;
  EXPECT_EQ(study_options(study_params_json(thrice)).repeat, 3);
  EXPECT_EQ(study_run_count(thrice), 13);  // the reference once, 2 schemes × 2 steps three times
  study::Options adaptive = sweep();
  adaptive.tolerances = {1e-3, 1e-4};
  EXPECT_EQ(study_options(study_params_json(adaptive)).tolerances, adaptive.tolerances);
  EXPECT_EQ(study_run_count(adaptive), 9);                          // and 2 schemes × 2 tolerances
  EXPECT_FALSE(study_params_json(sweep()).contains("tolerances"));  // a fixed-step study's JSON as before
  EXPECT_EQ(parse_scheme("hht"), model::Scheme::hht);
  EXPECT_FALSE(parse_scheme("newmark"));
}

TEST(StudyJob, TheTableReadsBackToTheSameCsvAndMarkdown) {
  study::Result r;
  r.reference_step = 0.001;
  r.reference_wall_seconds = 0.5;
  r.rows.push_back({"midpoint", 0.04, 5, true, "", 1.5e-3, 9e-3, 1e-12, 0.25, 27, 5.4});
  r.rows.push_back({"hht", 0.02, 3, false, "step 4 did not converge", NAN, 0.1, 0.2, 0.1, 70, 23.3});
  const study::Result back = study_result_from_json(nlohmann::json::parse(study::to_json(r).dump()));
  EXPECT_EQ(study::to_csv(back), study::to_csv(r));
  EXPECT_EQ(study::to_markdown(back), study::to_markdown(r));
  EXPECT_EQ(back.rows[1].failure, "step 4 did not converge");
  EXPECT_EQ(study::to_json(back), study::to_json(r));
}

class StudyRun : public ::testing::Test {
 protected:
  test::TempDir dir;
  JobFiles files{dir.path()};
  ManualClock clock;
  std::ostringstream log;
  std::atomic<bool> cancel{false};
  std::vector<Progress> reports;
  ProgressSink sink = [this](const Progress& p) { reports.push_back(p); };
  model::Model model = scene::load(test::box_scene(1, 20, {0, 0, 0}, 2.0));

  Outcome run(const Job& job) {
    const AttemptFiles attempt = files.prepare_attempt(job.id, 1);
    return run_study_job(job, model, {attempt, clock, 0, log, cancel, sink});
  }
};

TEST_F(StudyRun, MatchesStudyRunAndCountsProgressInRuns) {
  const Job job = study_job(sweep());
  const Outcome outcome = run(job);
  ASSERT_EQ(outcome.status, Status::succeeded) << log.str();
  EXPECT_EQ((*outcome.summary)["runs_done"], 5);
  ASSERT_FALSE(reports.empty());
  for (const Progress& p : reports) EXPECT_EQ(p.steps, 5);
  EXPECT_EQ(reports.back().step, 5);
  EXPECT_TRUE(std::is_sorted(reports.begin(), reports.end(),
                             [](const Progress& a, const Progress& b) { return a.step < b.step; }));

  std::ifstream in(files.attempt(job.id, 1).study());
  const study::Result served = study_result_from_json(nlohmann::json::parse(in));
  const study::Result expected = study::run(model, sweep());  // the CLI's sweep
  ASSERT_EQ(served.rows.size(), expected.rows.size());
  for (std::size_t i = 0; i < served.rows.size(); ++i) {
    EXPECT_EQ(served.rows[i].scheme, expected.rows[i].scheme);
    EXPECT_EQ(served.rows[i].steps, expected.rows[i].steps);
    EXPECT_DOUBLE_EQ(served.rows[i].displacement_error, expected.rows[i].displacement_error) << i;
    EXPECT_DOUBLE_EQ(served.rows[i].energy_error, expected.rows[i].energy_error) << i;
  }
}

TEST_F(StudyRun, StopsWhenCanceledAndWritesNoTable) {
  const Job job = study_job(sweep());
  cancel = true;
  const Outcome outcome = run(job);
  EXPECT_EQ(outcome.status, Status::canceled);
  EXPECT_FALSE((*outcome.summary)["completed"].get<bool>());
  EXPECT_FALSE(std::filesystem::exists(files.attempt(job.id, 1).study()));
  EXPECT_NE(log.str().find("canceled after 0 of 5 runs"), std::string::npos) << log.str();
}

}  // namespace
}  // namespace stoss::server::jobs
