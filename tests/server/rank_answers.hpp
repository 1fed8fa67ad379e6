#pragma once
/// @file Test support for runs on several MPI ranks (issue 27 §3): the seed's example in contact, the
/// comparison of a run of one rank with a run of two, and a TMPDIR whose rank folders can be counted.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/server/live_server.hpp"

namespace stoss::test {

/// True on a machine of one hardware thread, where mpiexec has one slot and 2 ranks are refused: the rank
/// tests skip there.
bool one_core();

/// The seed's example (api/examples/hollow_ball_plate.json) with the ball 0.005 above the plate: its 20
/// steps of 0.01 all have the ball in contact. solver.linear as given.
nlohmann::json seed_in_contact_scene(const std::string& linear, int checkpoint_every = 0);
/// seed_in_contact_scene written to dir/seed_<linear>.json; its path.
std::string seed_in_contact(const TempDir& dir, const std::string& linear, int checkpoint_every = 0);

/// The results in `one` and `two` (folders of result.h5) agree as §3 asks: energy and momentum series within
/// 1e-9 relative, final positions within 1e-9 of the scene's size; both keep energy per step within 1e-10;
/// 20 steps, every one in contact.
void expect_the_same_answers(const std::filesystem::path& one, const std::filesystem::path& two);

/// The id of a job just submitted.
std::string id_of(const httplib::Result& r);
/// The processes whose command line names `job_id`: the launcher and the ranks of that job.
int processes_of(const std::string& job_id);
/// The server flags of a service that runs jobs of up to 2 ranks, then `more`.
std::vector<std::string> two_rank_service(std::vector<std::string> more = {});
/// box_scene for minutes on 2 ranks.
nlohmann::json long_two_rank_scene();

/// The seed's example in contact (petsc_gamg) submitted as a job of 1 rank and as one of 2, both waited for:
/// their ids and last job JSON. Fails the test (with the two-rank job's log) unless both succeeded.
struct OneAndTwoRankJobs {
  std::string one, two;
  nlohmann::json one_job, two_job;
};
OneAndTwoRankJobs seed_jobs_on_one_and_two_ranks(httplib::Client& c);
/// The folder of the attempt that ended `job` (its last job JSON) in the data directory `data`: the first,
/// unless a lease lost under load gave the job to a second. Fails the test, naming what the job's folder
/// holds, when it has no result.h5.
std::filesystem::path last_attempt(const std::filesystem::path& data, const nlohmann::json& job);

/// TMPDIR for the test's runs, which rank k > 0 makes its private directory in (core/run/ranks.hpp); empty
/// again once they ended. Restored by the destructor.
class PrivateTemp {
 public:
  explicit PrivateTemp(const TempDir& dir);
  ~PrivateTemp();
  /// What ranks left behind: nothing.
  std::vector<std::string> rank_directories_left() const;

 private:
  std::filesystem::path path_;
};

}  // namespace stoss::test
