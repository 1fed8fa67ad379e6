// The launcher of a job on several ranks (server/jobs/running/launcher.hpp, issue 27 §5): a template of words
// whose {ranks} becomes the job's ranks, the rank's command after it, "…" marking its place as the docs
// write it; a template it cannot start is refused with the rule.
#include <gtest/gtest.h>

#include "server/jobs/running/launcher.hpp"

namespace stoss::server::jobs {
namespace {

using Words = std::vector<std::string>;

TEST(Launcher, RanksAreFilledInAndTheRanksCommandGoesLast) {
  EXPECT_EQ(launcher_command("srun -n {ranks} --mpi=pmix …", 4, {"stoss", "run-job"}),
            (Words{"srun", "-n", "4", "--mpi=pmix", "stoss", "run-job"}));
  EXPECT_EQ(launcher_command("mpiexec  -np {ranks}  --host a:{ranks} ...", 2, {"x"}),
            (Words{"mpiexec", "-np", "2", "--host", "a:2", "x"}));
  EXPECT_EQ(launcher_command("wrap.sh", 3, {"x"}), (Words{"wrap.sh", "x"}));
}

TEST(Launcher, TheDefaultIsOpenMpisMpiexecWithRootsFlagOnlyAsRoot) {
  EXPECT_EQ(launcher_command(default_launcher(false), 2, {"x"}),
            (Words{"mpiexec", "-n", "2", "--use-hwthread-cpus", "--bind-to", "none", "x"}));
  EXPECT_EQ(
      launcher_command(default_launcher(true), 2, {"x"}),
      (Words{"mpiexec", "-n", "2", "--allow-run-as-root", "--use-hwthread-cpus", "--bind-to", "none", "x"}));
  EXPECT_EQ(launcher_problem(default_launcher(true)), std::nullopt);
}

TEST(Launcher, ATemplateWithoutAProgramOrWithQuotesIsRefusedWithTheRule) {
  EXPECT_EQ(*launcher_problem("  "),
            "--launcher needs a program to run, such as 'mpiexec -n {ranks}', got '  '");
  EXPECT_NE(launcher_problem("… -n {ranks}")->find("needs a program to run"), std::string::npos);
  EXPECT_NE(launcher_problem("srun --export='A B' -n {ranks}")->find("without quotes or backslashes"),
            std::string::npos);
}

}  // namespace
}  // namespace stoss::server::jobs
