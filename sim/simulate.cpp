#include "sim/simulate.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "base/check.h"
#include "base/error.h"
#include "sim/grid/grid_builder.h"
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

namespace {

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

SimulationResult simulate_grid(const Scenario& scenario, const std::vector<double>& times,
                               const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  SimulationResult result;
  result.scenario = scenario;
  EnthalpySolver solver(build_grid_problem(scenario));
  result.reference_energy_j = solver.reference_energy();
  const auto total = static_cast<std::int64_t>(times.size());
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (times[i] > solver.time()) solver.advance_to(times[i]);
    result.snapshots.push_back(grid_snapshot(solver.snapshot()));
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
                          const ProgressCallback& progress) {
  validate_scenario(scenario);
  if (times.empty()) throw UserError("", "output times", "at least one output time is needed");
  for (std::size_t i = 0; i < times.size(); ++i)
    if (!std::isfinite(times[i]) || times[i] < 0 || (i > 0 && !(times[i] > times[i - 1])))
      throw UserError("", "output times", "must be finite, >= 0 and increasing");
  if (scenario.grid != GridGeometry::none) return simulate_grid(scenario, times, progress);
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
