// Cost of the grid solver with natural convection in the water (issue 24) on
// data/scenarios/hollow_sphere_flow.toml (the default's shell, axisymmetric, 0.5 mm cells),
// over a short stretch of simulated time (the cost per simulated second is nearly steady once
// the flow has started). Target (issue 24): the whole scenario in at most 30 s on 2 cores.
// Prints per run: cells, threads, wall and CPU time, enthalpy steps, flow steps, flow cell
// updates per CPU second (cells x flow steps / CPU s), and the whole hour's CPU extrapolated;
// then 2 threads against 1 (same process). On a shared machine quote CPU times and ratios.
// Usage: bench_flow [SIMULATED_SECONDS (default 20) [scenario.toml]]
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>

#include "sim/format/scenario_file.h"
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
  const double cells = static_cast<double>(f.cells[0]) * f.cells[1] * f.cells[2];
  std::printf(
      "grid %dx%d  threads %d  simulated %.0f s  wall %.2f s  cpu %.2f s  steps %ld  "
      "flow steps %ld  %.3g flow cell updates/cpu s  whole %.0f s: ~%.0f cpu s\n",
      f.cells[0], f.cells[1], threads, seconds, out.wall_s, out.cpu_s, s.steps, s.flow_steps,
      cells * static_cast<double>(s.flow_steps) / out.cpu_s, full_duration_s,
      out.cpu_s * full_duration_s / seconds);
  std::fflush(stdout);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 20.0;
  const std::string file =
      argc > 2 ? argv[2] : std::string(THAW_SOURCE_DIR) + "/data/scenarios/hollow_sphere_flow.toml";
  const thaw::sim::Scenario sc = thaw::sim::read_scenario_file(file);
  const Run one = run(sc, 1, seconds, sc.duration_s);
  const Run two = run(sc, 2, seconds, sc.duration_s);
  std::printf("2 threads vs 1: wall %.2fx faster, cpu %.2fx\n", one.wall_s / two.wall_s,
              two.cpu_s / one.cpu_s);
  return 0;
}
