#include "sim/simulate.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <thread>

#include <unistd.h>

#include "base/check.h"
#include "base/error.h"
#include "base/interrupt.h"
#include "base/number_text.h"
#include "sim/grid/grid_builder.h"
#include "sim/grid/grid_rules.h"
#include "sim/scenario/scenario_rules.h"

namespace thaw::sim {

std::vector<InterfaceRecord> SimulationResult::interface_records() const {
  std::vector<InterfaceRecord> rows;
  rows.reserve(snapshots.size());
  for (std::size_t i = 0; i < snapshots.size(); ++i) {
    const Snapshot& s = snapshots[i];
    rows.push_back({static_cast<long>(i), s.time_s, s.inner_radius_m, s.outer_radius_m,
                    s.liquid_volume_m3, s.ice_volume_m3, s.energy_balance_error});
  }
  return rows;
}

std::vector<double> output_times(const Scenario& sc) {
  std::vector<double> times;
  const double n = std::floor(sc.duration_s / sc.output_interval_s * (1 + 1e-12));
  for (long k = 0; k <= static_cast<long>(n); ++k)
    times.push_back(std::min(static_cast<double>(k) * sc.output_interval_s, sc.duration_s));
  if (times.back() < sc.duration_s) times.push_back(sc.duration_s);
  return times;
}

double field_bytes(const GridField& grid, std::size_t outputs) {
  return (grid.has_velocity() ? 6.0 : 3.0) * sizeof(float) *
         static_cast<double>(grid.cell_count()) * static_cast<double>(outputs);
}

namespace {

/// The machine's physical memory [bytes] (sysconf(3)), 0 if unknown.
double physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
}

/// "1.8 GB" (decimal units).
std::string bytes_text(double bytes) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB"};
  int u = 0;
  while (bytes >= 1000 && u < 5) bytes /= 1000, ++u;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g %s", bytes, units[u]);
  return buf;
}

/// Issue 27: output_interval_s = 0.0036 s on a grid run (1e6 outputs, which the rules allow) kept
/// every field in memory, grew about 68 MB/s and ended in "out of memory", exit 3. Fields kept in
/// memory may take at most half of the physical memory (the solver, and thaw run's mesher after
/// it, need the rest); the message names the key, the outputs and the bytes.
void check_fields_fit_in_memory(const Scenario& sc, const GridField& grid, std::size_t outputs) {
  const double need = field_bytes(grid, outputs), memory = physical_memory_bytes();
  if (memory <= 0 || need <= 0.5 * memory) return;
  const double per_output = field_bytes(grid, 1);
  const double most = std::floor(0.5 * memory / per_output);
  throw UserError(
      "", "simulation.output_interval_s",
      "(" + shortest_text(sc.output_interval_s) + " s) asks for " + std::to_string(outputs) +
          " outputs of " + std::to_string(grid.cell_count()) + " cells (" + bytes_text(per_output) +
          " each, " + bytes_text(need) + " in all), more than half of this machine's " +
          bytes_text(memory) + " of memory; at most " + shortest_text(most) +
          " outputs fit (output_interval_s >= " +
          shortest_text(sc.duration_s / std::max(1.0, most - 1)) +
          " s), or use thaw simulate, which writes each field to disk as it is reached");
}

/// Radius of the sphere of volume v [m]: interfaces.csv's radii for grid runs.
double volume_equivalent_radius(double v) {
  return std::cbrt(3 * v / (4 * std::numbers::pi));
}

Snapshot grid_snapshot(const GridSnapshot& g) {
  Snapshot s;
  s.time_s = g.time_s;
  s.liquid_volume_m3 = g.liquid_volume_m3;
  s.ice_volume_m3 = g.ice_volume_m3;
  s.inner_radius_m = volume_equivalent_radius(g.liquid_volume_m3);
  s.outer_radius_m = volume_equivalent_radius(g.liquid_volume_m3 + g.ice_volume_m3);
  s.energy_balance_error = g.energy_balance_error;
  s.enthalpy_j = g.enthalpy_j;
  s.heat_in_j = g.heat_in_j;
  s.drained_j = g.drained_j;
  return s;
}

/// The grid solver's runaway as the user's error, naming the key most likely behind it.
[[noreturn]] void throw_runaway(const Scenario& scenario, const GridRunaway& e) {
  std::string key = "simulation.max_step_s", hint;
  if (e.at_max_step) {
    hint =
        "its value " + shortest_text(scenario.max_step_s) + " s caps every step; use a larger one";
  } else {
    const LikelyCause cause = likely_cause_of_solver_failure(scenario);
    key = cause.key, hint = cause.hint;
    if (key == "simulation.time_tolerance") {  // the 1D key; a grid's steps follow its cells
      key = "simulation.cell_size_m";
      hint = "every value is in its typical range; try larger cells (now " +
             shortest_text(effective_cell_size_m(scenario)) + " m)";
    }
  }
  throw UserError(scenario.source_name, "key '" + key + "'",
                  std::string("the grid solver cannot continue: ") + e.what() + "; " + hint);
}

/// Advances the grid solver to t, stopping within a step's Newton or CG iteration when an
/// interrupt arrives (SIGINT, SIGTERM or request_interrupt()). Then the caller's callback decides
/// (interruptible() throws Interrupted; the GUI's throws its own cancel); a flag raised by
/// someone else (the GUI's film cancel) is waited out, and the run goes on where it stopped.
void advance_grid(EnthalpySolver& solver, double t, const ProgressCallback& progress,
                  std::int64_t done, std::int64_t total) {
  while (!solver.finished() && solver.time() < t) {
    solver.advance_to(t, [] { return interrupt_requested(); });
    if (solver.finished() || solver.time() >= t) return;
    if (!progress) throw_if_interrupted();
    while (interrupt_requested()) {
      progress(done, total);  // the same count again: may throw
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
}

SimulationResult simulate_grid(const Scenario& scenario, const std::vector<double>& times,
                               const ProgressCallback& progress, const FieldSink& sink) {
  const auto start = std::chrono::steady_clock::now();
  SimulationResult result;
  result.scenario = scenario;
  EnthalpySolver solver(build_grid_problem(scenario));
  {
    GridField first = solver.field();
    if (!sink) check_fields_fit_in_memory(scenario, first, times.size());
    first.temperature_c.clear(), first.ice_fraction.clear(), first.water_fraction.clear();
    first.velocity_m_s.clear();
    result.grid = std::move(first);
  }
  result.reference_energy_j = solver.reference_energy();
  result.boundary_faces = solver.face_names();
  const auto total = static_cast<std::int64_t>(times.size());
  for (std::size_t i = 0; i < times.size(); ++i) {
    try {
      if (times[i] > solver.time())
        advance_grid(solver, times[i], progress, static_cast<std::int64_t>(i), total);
    } catch (const GridRunaway& e) {
      throw_runaway(scenario, e);
    }
    const GridSnapshot g = solver.snapshot();
    result.snapshots.push_back(grid_snapshot(g));
    result.boundary_heat_j.push_back(g.face_heat_in_j);
    if (scenario.natural_convection)
      result.flow_records.push_back({g.time_s, g.max_speed_m_s, g.rayleigh});
    result.water_records.push_back(
        {g.time_s, g.held_water_m3,
         std::isfinite(g.water_level_m) ? g.water_level_m
                                        : std::numeric_limits<double>::quiet_NaN(),
         g.enclosed_liquid_volume_m3, g.liquid_volume_m3, g.ice_volume_m3, g.drained_m3});
    if (sink)
      sink(i, solver.field());
    else
      result.fields.push_back(solver.field());
    if (progress) progress(static_cast<std::int64_t>(i + 1), total);
    if (solver.finished()) {
      result.ended_early = i + 1 < times.size();
      break;
    }
  }
  result.grid_events = solver.events();
  const auto& c = scenario.shape.outer.center_m;
  for (const GridEvent& e : result.grid_events) {
    const double dx = e.position_m[0] - c[0], dy = e.position_m[1] - c[1],
                 dz = e.position_m[2] - c[2];
    result.events.push_back({e.kind, e.time_s, std::sqrt(dx * dx + dy * dy + dz * dz)});
  }
  result.grid_statistics = solver.statistics();
  result.statistics.steps =
      result.grid_statistics.steps;  // for the command line's one-line summary
  result.statistics.rejected_steps = result.grid_statistics.rejected_steps;
  result.statistics.max_step_energy_error = result.grid_statistics.max_step_energy_error;
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace

SimulationResult simulate(const Scenario& scenario, const std::vector<double>& times,
                          const ProgressCallback& progress, const FieldSink& sink) {
  validate_scenario(scenario);
  if (times.empty()) throw UserError("", "output times", "at least one output time is needed");
  for (std::size_t i = 0; i < times.size(); ++i)
    if (!std::isfinite(times[i]) || times[i] < 0 || (i > 0 && !(times[i] > times[i - 1])))
      throw UserError("", "output times", "must be finite, >= 0 and increasing");
  if (scenario.grid != GridGeometry::none) return simulate_grid(scenario, times, progress, sink);
  const auto start = std::chrono::steady_clock::now();
  SimulationResult result;
  result.scenario = scenario;
  FrontFixingSolver solver(scenario);
  result.reference_energy_j = solver.reference_energy();
  const auto total = static_cast<std::int64_t>(times.size());
  for (std::size_t i = 0; i < times.size(); ++i) {
    // A small-time analytic start (zero-thickness phase) begins the integration at t0 > 0,
    // at most 5 % of an output interval: t = 0 shows the scenario's own initial state, any
    // other output time before t0 the start state.
    if (times[i] > solver.time()) solver.advance_to(times[i]);
    Snapshot snap =
        times[i] == 0 && solver.time() > 0 ? solver.initial_snapshot(true) : solver.snapshot(true);
    if (solver.finished() && solver.time() < times[i]) {
      result.snapshots.push_back(std::move(snap));
      result.ended_early = true;
      break;
    }
    snap.time_s = times[i];
    result.snapshots.push_back(std::move(snap));
    if (progress) progress(static_cast<std::int64_t>(i + 1), total);
    if (solver.finished()) {
      result.ended_early = i + 1 < times.size();
      break;
    }
  }
  result.events = solver.events();
  result.statistics = solver.statistics();
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

SimulationResult simulate(const Scenario& scenario, const ProgressCallback& progress) {
  validate_scenario(scenario);
  return simulate(scenario, output_times(scenario), progress);
}

}  // namespace thaw::sim
