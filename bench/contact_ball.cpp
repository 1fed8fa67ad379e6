// Whole-run benchmark of the seed's example (api/examples/hollow_ball_plate.json: 432-element hollow
// ball onto a free 512-element plate, 100 steps of h = 0.01, frictionless Lagrange contact) with each
// scheme: wall seconds, Newton iterations per step and the share of time in the linear solver.
// Target (2 cores): the energy_momentum run in under 2 s.
// Run: ./build/bench_contact_ball
#include <benchmark/benchmark.h>

#include "core/scene/scene.hpp"
#include "core/simulate.hpp"

namespace {

void run(benchmark::State& state, stoss::model::Scheme scheme) {
  stoss::model::Model m =
      stoss::scene::load_file(std::string(STOSS_SOURCE_DIR) + "/api/examples/hollow_ball_plate.json");
  m.time.scheme = scheme;
  stoss::model::Observer quiet;
  stoss::model::Summary s;
  for (auto _ : state) s = stoss::simulate(m, quiet);
  state.counters["steps"] = s.steps;
  state.counters["wall_s"] = s.wall_seconds;
  state.counters["newton_per_step"] = s.newton_iterations_per_step;
  state.counters["linear_solver_share"] = s.linear_solver_seconds / s.wall_seconds;
  state.counters["energy_drift"] = s.energy_drift;
  state.counters["max_penetration"] = s.max_penetration;
}

}  // namespace

BENCHMARK_CAPTURE(run, energy_momentum, stoss::model::Scheme::energy_momentum)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->Repetitions(3)
    ->ReportAggregatesOnly(false);
BENCHMARK_CAPTURE(run, midpoint, stoss::model::Scheme::midpoint)->Unit(benchmark::kSecond)->Iterations(1);

BENCHMARK_MAIN();
