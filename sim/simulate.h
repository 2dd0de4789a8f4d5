#pragma once
// The simulation as a library call, for `thaw simulate` and the `thaw run` pipeline: run a
// scenario, sampling the state at exactly the requested output times. Part of the sim core (no
// TOML, no JSON): the result folder is written by sim/format/simulation_output.h. Knows nothing of
// the command line; progress goes through a callback.
#include <array>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <vector>

#include "base/progress.h"
#include "sim/grid/enthalpy_solver.h"
#include "sim/grid/grid_field.h"
#include "sim/scenario/geometry.h"
#include "sim/scenario/interface_record.h"
#include "sim/scenario/scenario.h"
#include "sim/stefan1d/front_fixing.h"

namespace thaw::sim {

struct SimulationResult {
  Scenario scenario;                ///< effective parameters (defaults filled in)
  std::vector<Snapshot> snapshots;  ///< one per output time reached (with profiles)
  std::vector<Event> events;
  SolverStatistics statistics;
  double reference_energy_j = 0;  ///< scale of energy_balance_error [J]
  double wall_time_s = 0;
  bool ended_early = false;  ///< no ice left before the last output time
  /// Grid runs (scenario.grid != none): one field per snapshot (empty when they were handed to
  /// a FieldSink instead), the events with positions (`events` holds them too, radius_m =
  /// distance from the outer body's centre).
  std::vector<GridField> fields;
  /// Grid runs: the grid itself (geometry, cells, origin, spacing; no cell values).
  GridField grid;
  std::vector<GridEvent> grid_events;
  GridStatistics grid_statistics;
  /// Grid runs with natural convection: per output time, {time [s], largest speed [m/s],
  /// Rayleigh number of the liquid}.
  std::vector<std::array<double, 3>> flow_records;
  /// Grid runs: the body's faces (sim/grid/body_faces.h) and, per snapshot, the heat that has
  /// entered the body through each since t = 0 [J] (boundary_heat.csv).
  std::vector<std::string> boundary_faces;
  std::vector<std::vector<double>> boundary_heat_j;
  /// Grid runs: the water's books per output time (summary.json "water"; docs/simulate.md,
  /// "Water held in an open shell").
  struct WaterRecord {
    double time_s = 0;
    double held_m3 = 0;      ///< held in opened cavities (cups)
    double level_m = 0;      ///< their lowest free surface (y) [m]; NaN: no cup holds water
    double enclosed_m3 = 0;  ///< liquid in sealed cavities and held in cups
    double liquid_m3 = 0;    ///< all liquid in the body
    double ice_m3 = 0;
    double drained_m3 = 0;  ///< drained so far (to the puddle)
  };
  std::vector<WaterRecord> water_records;
  /// interfaces.csv rows, step = index into snapshots.
  std::vector<InterfaceRecord> interface_records() const;
};

/// Receives each output step's field of a grid run as it is reached (step = index into the
/// output times), so that the run keeps none of them in memory: the result folder's writer
/// streams them to disk (sim/format/simulation_output.h).
using FieldSink = std::function<void(std::size_t step, const GridField& field)>;

/// Bytes of the fields a grid run keeps for `outputs` output times on `grid`: three floats per
/// cell per output (temperature, ice and water fractions), six with the flow's velocity.
double field_bytes(const GridField& grid, std::size_t outputs);

/// The output times of a scenario: 0, interval, 2 interval, ... and duration_s (exactly
/// k * interval, computed as a product, never by accumulation).
std::vector<double> output_times(const Scenario& scenario);

/// Runs `scenario` (validated here; throws thaw::UserError if invalid) and samples the state at
/// each of `times` (increasing, >= 0); t = 0 is the scenario's initial state even when a phase
/// of zero thickness is started analytically a moment later. If the ice is gone before the last
/// time, the run stops there and the last snapshot is that instant (ended_early). progress(done,
/// total) is called after each output time. A grid run hands each field to `sink` when given;
/// without one it keeps them all in `fields`, and refuses up front (a UserError on
/// simulation.output_interval_s naming the outputs and bytes) when they would take more than half
/// of the machine's memory.
SimulationResult simulate(const Scenario& scenario, const std::vector<double>& times,
                          const ProgressCallback& progress = {}, const FieldSink& sink = {});
/// simulate(scenario, output_times(scenario), progress).
SimulationResult simulate(const Scenario& scenario, const ProgressCallback& progress = {});

}  // namespace thaw::sim
