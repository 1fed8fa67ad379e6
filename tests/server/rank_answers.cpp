#include "tests/server/rank_answers.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <thread>

#include "core/output/result_reader.hpp"

namespace stoss::test {

namespace fs = std::filesystem;

namespace {

double relative_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / a.cwiseAbs().maxCoeff();
}

double largest_energy_step(const output::ResultFile& r) {
  const Eigen::VectorXd H = r.series("total_energy").col(0);
  double largest = 0;
  for (Eigen::Index n = 1; n < H.size(); ++n)
    largest = std::max(largest, std::abs(H(n) - H(n - 1)) / std::abs(H(0)));
  return largest;
}

}  // namespace

std::string id_of(const httplib::Result& r) {
  return body_json(r)["id"].get<std::string>();
}

int processes_of(const std::string& job_id) {
  int found = 0;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    std::ifstream in(entry.path() / "cmdline", std::ios::binary);
    const std::string command(std::istreambuf_iterator<char>(in), {});
    if (command.find(job_id) != std::string::npos) ++found;
  }
  return found;
}

std::vector<std::string> two_rank_service(std::vector<std::string> more) {
  std::vector<std::string> flags{"--workers", "1", "--max-ranks-per-job", "2", "--ranks-per-job", "2"};
  flags.insert(flags.end(), more.begin(), more.end());
  return flags;
}

nlohmann::json long_two_rank_scene() {
  nlohmann::json scene = box_scene(6, 100'000, {1, 0, 0}, 2.0);
  scene["solver"]["ranks"] = 2;
  return scene;
}

OneAndTwoRankJobs seed_jobs_on_one_and_two_ranks(httplib::Client& c) {
  using namespace std::chrono_literals;
  nlohmann::json scene = seed_in_contact_scene("petsc_gamg");
  OneAndTwoRankJobs jobs;
  jobs.one = id_of(submit(c, scene));
  scene["solver"]["ranks"] = 2;
  jobs.two = id_of(submit(c, scene));
  jobs.one_job = wait_for_status(c, jobs.one, {"succeeded", "failed", "canceled"}, 180s);
  jobs.two_job = wait_for_status(c, jobs.two, {"succeeded", "failed", "canceled"}, 180s);
  EXPECT_EQ(jobs.one_job["status"], "succeeded") << jobs.one_job.dump();
  EXPECT_EQ(jobs.two_job["status"], "succeeded")
      << jobs.two_job.dump() << c.Get("/v1/jobs/" + jobs.two + "/log")->body;
  return jobs;
}

fs::path last_attempt(const fs::path& data, const nlohmann::json& job) {
  const fs::path folder = data / "jobs" / job["id"].get<std::string>();
  const fs::path attempt = folder / ("attempt-" + std::to_string(job["attempt"].get<int>()));
  if (!fs::exists(attempt / "result.h5")) {  // what is there instead, for the failure's message
    std::string listing;
    std::error_code error;
    for (const auto& entry : fs::recursive_directory_iterator(folder, error))
      listing += " " + entry.path().lexically_relative(folder).string();
    ADD_FAILURE() << "no result.h5 in " << attempt << " for " << job.dump()
                  << "; the job's folder holds:" << listing;
  }
  return attempt;
}

bool one_core() {
  return std::thread::hardware_concurrency() < 2;
}

nlohmann::json seed_in_contact_scene(const std::string& linear, int checkpoint_every) {
  std::ifstream in(std::string(STOSS_SOURCE_DIR) + "/api/examples/hollow_ball_plate.json");
  nlohmann::json scene = nlohmann::json::parse(in);
  scene["bodies"][0]["mesh"]["hollow_sphere"]["center"][2] = 1.005;
  scene["time"]["end"] = 0.2;
  scene["solver"]["linear"] = linear;
  if (checkpoint_every > 0) scene["output"]["checkpoint_every"] = checkpoint_every;
  return scene;
}

std::string seed_in_contact(const TempDir& dir, const std::string& linear, int checkpoint_every) {
  const fs::path path = dir.path() / ("seed_" + linear + ".json");
  std::ofstream(path) << seed_in_contact_scene(linear, checkpoint_every).dump(1);
  return path.string();
}

void expect_the_same_answers(const fs::path& one, const fs::path& two) {
  const auto a = output::ResultFile::open(one / "result.h5");
  const auto b = output::ResultFile::open(two / "result.h5");
  ASSERT_EQ(a.series("time").rows(), 21);
  ASSERT_EQ(b.series("time").rows(), 21);
  EXPECT_GT(b.series("contact_area").col(0).tail(20).minCoeff(), 0) << "every step in contact";
  for (const std::string name : {"total_energy", "linear_momentum", "angular_momentum"})
    EXPECT_LT(relative_difference(a.series(name), b.series(name)), 1e-9) << name;
  const Eigen::MatrixXd x = a.frame_positions(a.frame_count() - 1),
                        y = b.frame_positions(b.frame_count() - 1);
  const double size = (x.colwise().maxCoeff() - x.colwise().minCoeff()).maxCoeff();
  EXPECT_LT((x - y).cwiseAbs().maxCoeff(), 1e-9 * size);
  EXPECT_LT(largest_energy_step(a), 1e-10);
  EXPECT_LT(largest_energy_step(b), 1e-10);
}

PrivateTemp::PrivateTemp(const TempDir& dir) : path_(dir.path() / "tmp") {
  fs::create_directories(path_);
  setenv("TMPDIR", path_.c_str(), 1);
}

PrivateTemp::~PrivateTemp() {
  unsetenv("TMPDIR");
}

std::vector<std::string> PrivateTemp::rank_directories_left() const {
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(path_))
    if (entry.path().filename().string().rfind("stoss-rank-", 0) == 0) left.push_back(entry.path());
  return left;
}

}  // namespace stoss::test
