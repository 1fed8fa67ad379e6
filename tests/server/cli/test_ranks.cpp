// `stoss run` on several MPI ranks (server/cli/ranks.hpp, issue 27 §1 and §3): --ranks N shall be refused
// with exit 2 outside 1 … cores, start mpiexec without itself, and a run on 2 ranks shall give the answers
// of 1 rank: on the seed's example through its impact (the ball moved down so that 20 steps are all contact),
// with GMRES + GAMG and with the direct solver (UMFPACK on one rank, MUMPS on two),
// the energy and momentum series agree within 1e-9 relative and the final positions within 1e-9 of the
// scene's size, and the energy–momentum bound (1e-10 per step) holds on both; so does a run of 1 rank killed
// and resumed on 2 (§4).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <thread>

#include "core/output/result_reader.hpp"
#include "server/cli/ranks.hpp"
#include "tests/server/live_server.hpp"
#include "tests/server/rank_answers.hpp"

namespace stoss {
namespace {

namespace fs = std::filesystem;

TEST(Ranks, BelowOneOrAboveTheCoresAreRefusedWithTheRule) {
  EXPECT_EQ(cli::ranks_problem(1, 2), std::nullopt);
  EXPECT_EQ(cli::ranks_problem(2, 2), std::nullopt);
  EXPECT_EQ(*cli::ranks_problem(0, 2), "--ranks must be at least 1, got 0");
  EXPECT_NE(cli::ranks_problem(3, 2)->find("--ranks must be at most the 2 cores of this machine, got 3"),
            std::string::npos);
}

TEST(Ranks, MpiexecRunsThisExecutableWithTheArgumentsButRanks) {
  const std::vector<std::string> args{"scene.json", "--ranks", "2", "-o", "out", "--strict"};
  EXPECT_EQ(cli::mpiexec_command(args, 2, false, "/bin/stoss"),
            (std::vector<std::string>{"mpiexec", "-n", "2", "--use-hwthread-cpus", "--bind-to", "none",
                                      "/bin/stoss", "run", "scene.json", "-o", "out", "--strict"}));
  const auto as_root = cli::mpiexec_command(args, 2, true, "/bin/stoss");
  EXPECT_EQ(as_root[3], "--allow-run-as-root");
}

TEST(Ranks, TheCommandLineRefusesRanksOutsideOneToTheCoresWithExit2) {
  test::TempDir dir;
  const std::string scene = std::string(STOSS_SOURCE_DIR) + "/api/examples/tumbling_bar.json";
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  for (const std::string& ranks : std::vector<std::string>{"0", "-1", std::to_string(cores + 1)}) {
    const test::CommandResult r =
        test::run_stoss({"run", scene, "-o", (dir.path() / "out").string(), "--ranks", ranks});
    EXPECT_EQ(r.exit_code, 2) << ranks << ": " << r.err;
    EXPECT_NE(r.err.find("--ranks must be"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir.path() / "out")) << "nothing started";
  }
  const test::CommandResult word = test::run_stoss({"run", scene, "--ranks", "two"});
  EXPECT_EQ(word.exit_code, 2);
  EXPECT_NE(word.err.find("--ranks N"), std::string::npos) << "the usage names it: " << word.err;
}

using test::expect_the_same_answers;
using test::PrivateTemp;
using test::seed_in_contact;

/// `scene` run on 1 rank into dir/one and on 2 into dir/two, both ending with exit 0 (asserted); what the
/// 2-rank run printed (stdout and stderr), or nothing when a run failed.
std::optional<std::string> run_on_one_and_two_ranks(const test::TempDir& dir, const std::string& scene) {
  const auto one =
      test::run_stoss({"run", scene, "-o", (dir.path() / "one").string()}, std::chrono::minutes(2));
  EXPECT_EQ(one.exit_code, 0) << one.err;
  const auto two = test::run_stoss({"run", scene, "-o", (dir.path() / "two").string(), "--ranks", "2"},
                                   std::chrono::minutes(2));
  EXPECT_EQ(two.exit_code, 0) << two.out << two.err;
  if (one.exit_code != 0 || two.exit_code != 0) return std::nullopt;
  return two.out + two.err;
}

TEST(Ranks, TwoRanksGiveTheSeedExampleOfOneRankThroughItsImpact) {
  if (test::one_core()) GTEST_SKIP() << "one core: --ranks 2 is refused here";
  test::TempDir dir;
  const PrivateTemp temp(dir);
  const auto ran = run_on_one_and_two_ranks(dir, seed_in_contact(dir, "petsc_gamg"));
  ASSERT_TRUE(ran);
  const std::string& printed = *ran;
  EXPECT_NE(printed.find("on 2 MPI ranks"), std::string::npos) << "the solver spans both ranks: " << printed;
  EXPECT_EQ(printed.find("on 2 MPI ranks"), printed.rfind("on 2 MPI ranks")) << "rank 1 prints nothing";
  EXPECT_EQ(printed.find("verdict: ok"), printed.rfind("verdict: ok")) << "rank 1 prints nothing";
  expect_the_same_answers(dir.path() / "one", dir.path() / "two");
  EXPECT_EQ(temp.rank_directories_left(), std::vector<std::string>{})
      << "rank 1's private directory is removed";

  const auto again = test::run_stoss({"run", "--resume", (dir.path() / "two").string(), "--ranks", "2"});
  EXPECT_EQ(again.exit_code, 0) << "every rank sees the run completed: " << again.err;
  EXPECT_NE(again.out.find("nothing to resume"), std::string::npos) << again.out;
  EXPECT_EQ(again.err, "");

  // The same run on 2 ranks again gives the same bits: the nodes' partition (PT-Scotch) repeats itself.
  const auto repeated = test::run_stoss(
      {"run", seed_in_contact(dir, "petsc_gamg"), "-o", (dir.path() / "repeated").string(), "--ranks", "2"},
      std::chrono::minutes(2));
  ASSERT_EQ(repeated.exit_code, 0) << repeated.err;
  const auto first = output::ResultFile::open(dir.path() / "two" / "result.h5");
  const auto second = output::ResultFile::open(dir.path() / "repeated" / "result.h5");
  for (const std::string name : {"total_energy", "linear_momentum", "angular_momentum"})
    EXPECT_EQ(first.series(name), second.series(name)) << name;
}

TEST(Ranks, ARunOfOneRankKilledResumesOnTwo) {
  if (test::one_core()) GTEST_SKIP() << "one core: --ranks 2 is refused here";
  test::TempDir dir;
  const PrivateTemp temp(dir);
  const std::string scene = seed_in_contact(dir, "petsc_gamg", 2);
  const auto whole =
      test::run_stoss({"run", scene, "-o", (dir.path() / "whole").string()}, std::chrono::minutes(2));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const fs::path killed = dir.path() / "killed";
  const pid_t pid = test::spawn_stoss({"run", scene, "-o", killed.string()}, dir.path() / "killed.log");
  ASSERT_TRUE(
      test::eventually([&] { return fs::exists(killed / "checkpoint/state.h5"); }, std::chrono::minutes(1)));
  ::kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "killed before its end (20 steps take seconds)";
  const auto resumed =
      test::run_stoss({"run", "--resume", killed.string(), "--ranks", "2"}, std::chrono::minutes(2));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.out << resumed.err;
  const std::string printed = resumed.out + resumed.err;
  EXPECT_NE(printed.find("resumed from step"), std::string::npos) << printed;
  EXPECT_NE(printed.find("on 2 MPI ranks"), std::string::npos) << printed;
  expect_the_same_answers(dir.path() / "whole", killed);
  EXPECT_EQ(temp.rank_directories_left(), std::vector<std::string>{})
      << "rank 1's private directory is removed";
}

TEST(Ranks, TheDirectSolverOnTwoRanksIsMumpsAndGivesTheAnswersOfUmfpack) {
  if (test::one_core()) GTEST_SKIP() << "one core: --ranks 2 is refused here";
  test::TempDir dir;
  const PrivateTemp temp(dir);
  const auto ran = run_on_one_and_two_ranks(dir, seed_in_contact(dir, "direct"));
  ASSERT_TRUE(ran);
  const std::string& printed = *ran;
  EXPECT_NE(printed.find("MUMPS LU through PETSc"), std::string::npos) << printed;
  EXPECT_NE(printed.find("on 2 MPI ranks"), std::string::npos) << printed;
  EXPECT_EQ(printed.find("Krylov solves"), std::string::npos) << "an LU is no Krylov method: " << printed;
  expect_the_same_answers(dir.path() / "one", dir.path() / "two");
}

/// GMRES cut to one iteration (PETSC_OPTIONS), so that every solve falls back to the LU of the whole matrix,
/// which each rank keeps: 2 ranks still give the answers of 1.
TEST(Ranks, TheLuFallbackOnTwoRanksGivesTheAnswersOfOneRank) {
  if (test::one_core()) GTEST_SKIP() << "one core: --ranks 2 is refused here";
  test::TempDir dir;
  const PrivateTemp temp(dir);
  setenv("PETSC_OPTIONS", "-stoss_ksp_max_it 1", 1);
  const auto ran = run_on_one_and_two_ranks(dir, seed_in_contact(dir, "petsc_gamg"));
  unsetenv("PETSC_OPTIONS");
  ASSERT_TRUE(ran);
  const std::regex line(R"((\d+) Krylov solves, .* (\d+) fell back to LU)");
  std::smatch counts;
  ASSERT_TRUE(std::regex_search(*ran, counts, line)) << *ran;
  EXPECT_GT(std::stoi(counts[1]), 20);
  EXPECT_EQ(counts[1], counts[2]) << "every solve fell back: " << counts[0];
  expect_the_same_answers(dir.path() / "one", dir.path() / "two");
}

TEST(Ranks, TheScenesSolverRanksStartsThatManyUnlessRanksSaysOtherwise) {
  if (test::one_core()) GTEST_SKIP() << "one core: 2 ranks are refused here";
  test::TempDir dir;
  const PrivateTemp temp(dir);
  nlohmann::json scene = test::seed_in_contact_scene("petsc_gamg");
  scene["time"]["end"] = 0.03;
  scene["solver"]["ranks"] = 2;
  const fs::path path = dir.path() / "two.json";
  std::ofstream(path) << scene.dump();
  const auto two = test::run_stoss({"run", path.string(), "-o", (dir.path() / "a").string()});
  ASSERT_EQ(two.exit_code, 0) << two.out << two.err;
  EXPECT_NE((two.out + two.err).find("on 2 MPI ranks"), std::string::npos) << two.out << two.err;
  EXPECT_NE(two.out.find("(resident, the sum over 2 MPI ranks)"), std::string::npos) << two.out;
  const auto one = test::run_stoss({"run", path.string(), "-o", (dir.path() / "b").string(), "--ranks", "1"});
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_EQ((one.out + one.err).find("MPI ranks"), std::string::npos) << "--ranks 1 wins: " << one.out;

  scene["solver"]["ranks"] = static_cast<int>(std::thread::hardware_concurrency()) + 1;
  std::ofstream(path) << scene.dump();
  const auto many = test::run_stoss({"run", path.string(), "-o", (dir.path() / "c").string()});
  EXPECT_EQ(many.exit_code, 2);
  EXPECT_NE(many.err.find("solver.ranks must be at most the"), std::string::npos) << many.err;

  // Started by hand on 2 ranks, the launcher's count rules over the scene's.
  const std::string command = "mpiexec -n 2 --bind-to none" +
                              std::string(geteuid() == 0 ? " --allow-run-as-root " : " ") + STOSS_BINARY +
                              " run " + path.string() + " -o " + (dir.path() / "d").string() + " 2>&1";
  std::string printed;
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  for (char chunk[4096]; std::fgets(chunk, sizeof chunk, pipe);) printed += chunk;
  EXPECT_EQ(pclose(pipe), 0) << printed;
  EXPECT_NE(printed.find("on 2 MPI ranks"), std::string::npos) << printed;
}

TEST(Ranks, ASceneAskingForASolverOfOneRankIsRefusedAtItsPointer) {
  if (test::one_core()) GTEST_SKIP() << "one core: --ranks 2 is refused here";
  test::TempDir dir;
  const auto r = test::run_stoss(
      {"run", seed_in_contact(dir, "iterative"), "-o", (dir.path() / "out").string(), "--ranks", "2"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("/solver/linear: \"iterative\" solves on one rank; on 2 MPI ranks it must be "
                       "\"petsc_gamg\", \"direct\" (MUMPS) or \"auto\""),
            std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace stoss
