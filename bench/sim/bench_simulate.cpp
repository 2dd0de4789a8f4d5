// Cost of the radial Stefan solver on the default scenario (one core; the solver is serial).
// Target (issue 2): one simulated hour of the default sphere under 50 ms at default accuracy.
//   BM_DefaultScenario      the built-in default as shipped: runs until the shell breaks through
//   BM_DefaultSphereOneHour the same sphere in gentler air (h = 20 W/m^2K) so that it is still
//                           intact after one full simulated hour
//   BM_SolverOnly           the default without writing profiles (solver and snapshots only)
#include <benchmark/benchmark.h>

#include "sim/format/scenario_file.h"
#include "sim/simulate.h"

namespace {

using thaw::sim::Scenario;

/// simulate() as the CLI and pipeline call it, with the simulated span and step count reported.
void run_simulate(benchmark::State& state, const Scenario& sc) {
  double simulated = 0;
  long steps = 0;
  for (auto _ : state) {
    const auto r = thaw::sim::simulate(sc);
    simulated = r.snapshots.back().time_s;
    steps = r.statistics.steps;
    benchmark::DoNotOptimize(r.snapshots.back().inner_radius_m);
  }
  state.counters["simulated_s"] = simulated;
  state.counters["steps"] = static_cast<double>(steps);
}

void BM_DefaultScenario(benchmark::State& state) {
  run_simulate(state, thaw::sim::default_scenario());
}
BENCHMARK(BM_DefaultScenario)->Unit(benchmark::kMillisecond);

void BM_DefaultSphereOneHour(benchmark::State& state) {
  Scenario sc = thaw::sim::default_scenario();
  sc.heat_transfer_coefficient_w_m2k = 20.0;
  run_simulate(state, sc);
}
BENCHMARK(BM_DefaultSphereOneHour)->Unit(benchmark::kMillisecond);

void BM_SolverOnly(benchmark::State& state) {
  const Scenario sc = thaw::sim::default_scenario();
  for (auto _ : state) {
    thaw::sim::FrontFixingSolver solver(sc);
    for (const double t : thaw::sim::output_times(sc)) {
      if (solver.finished()) break;
      if (t > solver.time()) solver.advance_to(t);
    }
    benchmark::DoNotOptimize(solver.snapshot(false).inner_radius_m);
  }
}
BENCHMARK(BM_SolverOnly)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
