// Whole-run benchmark of the seed's example (api/examples/hollow_ball_plate.json: 432-element hollow
// ball onto a free 512-element plate, 100 steps of h = 0.01, frictionless Lagrange contact) with each
// scheme and master surface: wall seconds, Newton iterations per step and the share of time in the
// linear solver. The smooth surface (the default, docs/smooth_master_surface.md) shall cost at most
// 1.5× the faceted one.
// Run: ./build/bench_contact_ball
#include <benchmark/benchmark.h>

#include "core/scene/scene.hpp"
#include "core/simulate.hpp"

namespace {

void run(benchmark::State& state, stoss::model::Scheme scheme, stoss::model::MasterSurface surface) {
  stoss::model::Model m =
      stoss::scene::load_file(std::string(STOSS_SOURCE_DIR) + "/api/examples/hollow_ball_plate.json");
  m.time.scheme = scheme;
  if (surface == stoss::model::MasterSurface::faceted) {  // the faceted comparator with its default rule
    m.contact.at(0).master_surface = surface;
    m.contact.at(0).switch_gap = stoss::model::SwitchGap::clamp;
  }
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

using stoss::model::MasterSurface;
using stoss::model::Scheme;
BENCHMARK_CAPTURE(run, energy_momentum_smooth, Scheme::energy_momentum, MasterSurface::smooth)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->Repetitions(3)
    ->ReportAggregatesOnly(false);
BENCHMARK_CAPTURE(run, energy_momentum_faceted, Scheme::energy_momentum, MasterSurface::faceted)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->Repetitions(3)
    ->ReportAggregatesOnly(false);
BENCHMARK_CAPTURE(run, midpoint_smooth, Scheme::midpoint, MasterSurface::smooth)
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

BENCHMARK_MAIN();
