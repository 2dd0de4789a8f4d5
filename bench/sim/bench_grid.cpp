// Cost of the grid (axisymmetric / 3D) Stefan solver on the shipped hollow cube
// (data/scenarios/hollow_cube.toml: one simulated hour or until the ice is gone).
// Target (issue 11): at most 30 s on 2 cores at default resolution. Prints, per run: cells,
// threads, wall and CPU time, steps, Newton and CG iterations, cell updates per CPU second
// (cells x Newton iterations / CPU time) and CG cell sweeps per CPU second (cells x CG
// iterations / CPU time); then 2 threads against 1 (wall and CPU, same process) and the cost
// per halving of the cell (CPU). On a shared machine quote CPU times and same-run ratios.
// Conduction only (flow = "none" whatever the file says): the water's flow has its own bench,
// bench_flow.
// Usage: bench_grid [scenario.toml [THREADS]] (default: the shipped hollow cube); with THREADS,
// only the default resolution on that many threads (for farm-bench pairs: 2 threads vs 1 as
// whole processes, alternating, so a drifting machine load affects both alike).
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
  long steps = 0;
};

Run run(thaw::sim::Scenario sc, int threads, double cell) {
  sc.cell_size_m = cell;
  omp_set_num_threads(threads);
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  const auto r = thaw::sim::simulate(sc);
  Run out;
  out.cpu_s = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto& s = r.grid_statistics;
  const auto& f = r.fields.front();
  out.steps = s.steps;
  const double cells = static_cast<double>(f.cells[0]) * f.cells[1] * f.cells[2];
  std::printf(
      "cell %.3g mm  grid %dx%dx%d  threads %d  wall %.2f s  cpu %.2f s  steps %ld  newton %ld  "
      "cg %ld  %.3g cell updates/cpu s  %.3g cg cell sweeps/cpu s  simulated %.0f s\n",
      cell * 1e3, f.cells[0], f.cells[1], f.cells[2], threads, out.wall_s, out.cpu_s, s.steps,
      s.newton_iterations, s.cg_iterations, static_cast<double>(s.cell_updates) / out.cpu_s,
      cells * static_cast<double>(s.cg_iterations) / out.cpu_s, r.snapshots.back().time_s);
  std::fflush(stdout);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string file =
      argc > 1 ? argv[1] : std::string(THAW_SOURCE_DIR) + "/data/scenarios/hollow_cube.toml";
  thaw::sim::Scenario sc = thaw::sim::read_scenario_file(file);
  sc.natural_convection = false;
  const double cell = thaw::sim::effective_cell_size_m(sc);
  if (argc > 2) {
    run(sc, std::atoi(argv[2]), cell);
    return 0;
  }
  const Run coarse = run(sc, 1, 2 * cell);
  const Run one = run(sc, 1, cell);
  const Run two = run(sc, 2, cell);
  std::printf("2 threads vs 1: wall %.2fx faster, CPU %.2fx (parallel overhead)\n",
              one.wall_s / two.wall_s, two.cpu_s / one.cpu_s);
  double load[3] = {0, 0, 0};
  if (getloadavg(load, 3) > 0)
    std::printf("load average at the end: %.2f %.2f %.2f\n", load[0], load[1], load[2]);
  std::printf("halving the cell (1 thread): CPU %.2fx, wall %.2fx (steps %.2fx)\n",
              one.cpu_s / coarse.cpu_s, one.wall_s / coarse.wall_s,
              static_cast<double>(one.steps) / static_cast<double>(coarse.steps));
  return 0;
}
