// Whole-run benchmark of the tumbling hollow sphere (api/examples/tumbling_sphere.json, 432 hex8,
// 200 steps of h = 0.01) with each scheme: wall seconds per step and Newton iterations per step.
// Run: ./build/bench_tumbling_sphere  (see docs/measurements.md, "Performance")
#include <benchmark/benchmark.h>

#include "core/scene/scene.hpp"
#include "core/simulate.hpp"

namespace {

void run(benchmark::State& state, stoss::model::Scheme scheme, const char* example) {
  stoss::model::Model m = stoss::scene::load_file(std::string(STOSS_SOURCE_DIR) + "/api/examples/" + example);
  m.time.scheme = scheme;
  stoss::model::Observer quiet;
  stoss::model::Summary s;
  for (auto _ : state) s = stoss::simulate(m, quiet);
  state.counters["steps"] = s.steps;
  state.counters["s_per_step"] = s.wall_seconds / s.steps;
  state.counters["newton_per_step"] = s.newton_iterations_per_step;
  state.counters["linear_solver_share"] = s.linear_solver_seconds / s.wall_seconds;
  state.counters["energy_drift"] = s.energy_drift;
}

}  // namespace

BENCHMARK_CAPTURE(run, energy_momentum, stoss::model::Scheme::energy_momentum, "tumbling_sphere.json")
    ->Unit(benchmark::kSecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(run, midpoint, stoss::model::Scheme::midpoint, "tumbling_sphere.json")
    ->Unit(benchmark::kSecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(run, energy_momentum_h005, stoss::model::Scheme::energy_momentum,
                  "tumbling_sphere_hard.json")
    ->Unit(benchmark::kSecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(run, midpoint_h005, stoss::model::Scheme::midpoint, "tumbling_sphere_hard.json")
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

BENCHMARK_MAIN();
