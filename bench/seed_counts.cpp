// The machine-independent counts of one run (issue 26): Newton iterations per step, symbolic analyses,
// numeric factorisations and linear solves of the whole process, with the summary's time split and the
// process's CPU seconds. Runs like `stoss run` (a checkpoint store in a scratch directory, so the checkpoint
// schedule's refactorisations happen as they do there).
// Run: ./build/bench_seed_counts [scene.json] [--steps] [--no-checkpoints]
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "core/scene/scene.hpp"
#include "core/simulate.hpp"
#include "core/solve/linear_solver.hpp"

namespace {

/// Newton iterations of every step, from the series newton_iterations.
class IterationLog : public stoss::model::Observer {
 public:
  void begin(const stoss::model::Model&, const stoss::model::SeriesLayout& layout) override {
    column_ = layout.index_of("newton_iterations");
  }
  void step(const stoss::model::StepRow& row) override {
    if (row.step > 0 && column_ >= 0) iterations.push_back(static_cast<int>(row.values[column_]));
  }
  std::vector<int> iterations;

 private:
  int column_ = -1;
};

double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene = std::string(STOSS_SOURCE_DIR) + "/api/examples/hollow_ball_plate.json";
  bool per_step = false, checkpoints = true;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--steps"))
      per_step = true;
    else if (!std::strcmp(argv[i], "--no-checkpoints"))
      checkpoints = false;
    else
      scene = argv[i];
  }
  const stoss::model::Model m = stoss::scene::load_file(scene);
  const std::filesystem::path scratch =
      std::filesystem::temp_directory_path() / ("seed_counts_" + std::to_string(::getpid()));
  IterationLog log;
  const stoss::model::Summary s = stoss::simulate(
      m, log, nullptr, checkpoints ? stoss::Checkpoints{scratch, false} : stoss::Checkpoints{});
  std::filesystem::remove_all(scratch);
  std::printf("steps %d iterations %d analyses %ld factorizations %ld solves %ld\n", s.steps,
              s.newton_iterations, stoss::solve::LinearSolver::process_analyses(),
              stoss::solve::LinearSolver::process_factorizations(),
              stoss::solve::LinearSolver::process_solves());
  std::printf(
      "seconds wall %.3f cpu %.3f factorization %.3f solve %.3f assembly %.3f contact %.3f output %.3f\n",
      s.wall_seconds, cpu_seconds(), s.linear_factorization_seconds, s.linear_solve_seconds,
      s.assembly_seconds, s.contact_seconds, s.output_seconds);
  std::printf("drift energy %.3e linear %.3e angular %.3e\n", s.energy_drift, s.linear_momentum_drift,
              s.angular_momentum_drift);
  if (per_step) {
    std::printf("iterations per step:");
    for (int n : log.iterations) std::printf(" %d", n);
    std::printf("\n");
  }
  return 0;
}
