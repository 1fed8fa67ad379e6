// A run's place in an MPI launch (core/parallel/mpi_place.hpp) shall come from Open MPI's variables, else
// from PMI's, else from an srun task's, and be {0, 1} when they are absent or make no sense, so that a stray
// variable never splits a run.
#include <gtest/gtest.h>

#include <cstdlib>

#include "core/parallel/mpi_place.hpp"

namespace stoss::parallel {
namespace {

/// Sets the four variables (nullptr: unset) for one test and restores none: each test sets all four.
void launch_environment(const char* ompi_rank, const char* ompi_size, const char* pmi_rank,
                        const char* pmi_size) {
  const auto set = [](const char* name, const char* value) {
    if (value)
      setenv(name, value, 1);
    else
      unsetenv(name);
  };
  set("OMPI_COMM_WORLD_RANK", ompi_rank);
  set("OMPI_COMM_WORLD_SIZE", ompi_size);
  set("PMI_RANK", pmi_rank);
  set("PMI_SIZE", pmi_size);
  for (const char* slurm : {"SLURM_PROCID", "SLURM_STEP_NUM_TASKS", "SLURM_NTASKS"}) unsetenv(slurm);
}

TEST(MpiPlace, IsRankZeroOfOneWithoutALauncher) {
  launch_environment(nullptr, nullptr, nullptr, nullptr);
  const MpiPlace place = mpi_place();
  EXPECT_EQ(place.rank, 0);
  EXPECT_EQ(place.size, 1);
  EXPECT_FALSE(place.several());
}

TEST(MpiPlace, ReadsOpenMpiFirstThenPmi) {
  launch_environment("1", "3", "0", "2");
  EXPECT_EQ(mpi_place().rank, 1);
  EXPECT_EQ(mpi_place().size, 3);
  EXPECT_TRUE(mpi_place().several());
  launch_environment(nullptr, nullptr, "1", "2");
  EXPECT_EQ(mpi_place().rank, 1);
  EXPECT_EQ(mpi_place().size, 2);
  launch_environment(nullptr, nullptr, nullptr, nullptr);
}

TEST(MpiPlace, ReadsAnSrunTaskButNotTheBatchScriptAroundIt) {
  launch_environment(nullptr, nullptr, nullptr, nullptr);
  setenv("SLURM_PROCID", "0", 1);  // sbatch -n 2: the script's own process, no step yet
  setenv("SLURM_NTASKS", "2", 1);
  EXPECT_EQ(mpi_place().size, 1) << "a script that runs stoss itself is one process";
  setenv("SLURM_PROCID", "1", 1);  // srun --mpi=pmix -n 2: PMIx sets no PMI_RANK
  setenv("SLURM_STEP_NUM_TASKS", "2", 1);
  EXPECT_EQ(mpi_place().rank, 1);
  EXPECT_EQ(mpi_place().size, 2);
  launch_environment(nullptr, nullptr, nullptr, nullptr);
}

TEST(MpiPlace, IgnoresValuesThatAreNoRankBelowASize) {
  for (const auto& [rank, size] :
       {std::pair{"2", "2"}, {"-1", "2"}, {"0", "0"}, {"x", "2"}, {"1", "2x"}, {"", "2"}}) {
    launch_environment(rank, size, nullptr, nullptr);
    EXPECT_EQ(mpi_place().size, 1) << rank << " of " << size;
    EXPECT_EQ(mpi_place().rank, 0) << rank << " of " << size;
  }
  launch_environment(nullptr, nullptr, nullptr, nullptr);
}

}  // namespace
}  // namespace stoss::parallel
