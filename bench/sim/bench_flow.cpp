// Cost of the grid solver with natural convection in the water (issue 24) on
// data/scenarios/hollow_sphere_flow.toml (the default's shell, axisymmetric, 0.5 mm cells) or
// another scenario. The flow is fastest in the first minute and slows as the water cools, so
// the cost of a short stretch does not extrapolate: the default runs the whole scenario.
// Target (issue 24): the hollow sphere in at most 30 s on 2 cores, the hollow cube with flow
// (3D) in at most 5 minutes. Prints per run: grid, threads, wall and CPU time, enthalpy steps,
// flow steps, flow cell updates (the flow box's cells x flow steps) per CPU second; then 2
// threads against 1 (same process). On a shared machine quote CPU times and ratios.
// With THREADS = "halving": one thread at the default cell and half of it over SIMULATED_SECONDS,
// and the CPU ratio (coarser cells than the default are refused with flow: the boundary layer).
// Usage: bench_flow [SIMULATED_SECONDS (default: the scenario's duration) [scenario.toml
//        [THREADS (default: 1 and 2) | halving]]]
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>

#include "sim/format/scenario_file.h"
#include "sim/grid/grid_rules.h"
#include "sim/simulate.h"

namespace {

struct Run {
  double wall_s = 0, cpu_s = 0;
};

Run run(thaw::sim::Scenario sc, int threads, double seconds, double full_duration_s) {
  sc.duration_s = seconds;
  sc.output_interval_s = seconds;
  omp_set_num_threads(threads);
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  const auto r = thaw::sim::simulate(sc);
  Run out;
  out.cpu_s = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto& s = r.grid_statistics;
  const auto& f = r.fields.front();
  std::printf(
      "grid %dx%dx%d  threads %d  simulated %.0f of %.0f s  wall %.2f s  cpu %.2f s  steps %ld  "
      "flow steps %ld  flow box cells %.0f on average  %.3g flow cell updates/cpu s\n",
      f.cells[0], f.cells[1], f.cells[2], threads, seconds, full_duration_s, out.wall_s, out.cpu_s,
      s.steps, s.flow_steps,
      s.flow_steps > 0 ? s.flow_cell_steps / static_cast<double>(s.flow_steps) : 0.0,
      s.flow_cell_steps / out.cpu_s);
  std::fflush(stdout);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string file =
      argc > 2 ? argv[2] : std::string(THAW_SOURCE_DIR) + "/data/scenarios/hollow_sphere_flow.toml";
  const thaw::sim::Scenario sc = thaw::sim::read_scenario_file(file);
  const double seconds = argc > 1 ? std::atof(argv[1]) : sc.duration_s;
  if (argc > 3 && std::string(argv[3]) == "halving") {
    const double h = thaw::sim::effective_cell_size_m(sc);
    double previous = 0;
    for (double cell : {h, h / 2}) {
      thaw::sim::Scenario fine = sc;
      fine.cell_size_m = cell;
      const Run r = run(fine, 1, seconds, sc.duration_s);
      if (previous > 0)
        std::printf("  cell %.4g mm: %.2fx the CPU of twice the cell\n", 1e3 * cell,
                    r.cpu_s / previous);
      previous = r.cpu_s;
    }
    return 0;
  }
  if (argc > 3) {
    run(sc, std::atoi(argv[3]), seconds, sc.duration_s);
    return 0;
  }
  const Run one = run(sc, 1, seconds, sc.duration_s);
  const Run two = run(sc, 2, seconds, sc.duration_s);
  std::printf("2 threads vs 1: wall %.2fx faster, cpu %.2fx\n", one.wall_s / two.wall_s,
              two.cpu_s / one.cpu_s);
  return 0;
}
