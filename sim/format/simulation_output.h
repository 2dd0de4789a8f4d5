#pragma once
// A simulation's result folder, written from a SimulationResult (sim/simulate.h): interfaces.csv,
// summary.json (every effective parameter, events, solver statistics) and profiles/step_NNNNNN.csv
// for the 1D geometries or fields/step_NNNNNN.grid and boundary_heat.csv for the grid ones. The
// sim's file-format layer: the solver core never sees these formats.
#include <filesystem>
#include <optional>
#include <string>

#include "sim/simulate.h"

namespace thaw::sim {

/// Writes interfaces.csv, profiles/step_NNNNNN.csv and summary.json into `dir` (which must
/// exist; use a thaw::StagingDirectory for an all-or-nothing result folder).
void write_simulation_outputs(const std::filesystem::path& dir, const SimulationResult& result);

/// A FieldSink (sim/simulate.h) that writes each field of a grid run to
/// DIR/fields/step_NNNNNN.grid as the solver reaches it, so no field stays in memory;
/// write_simulation_outputs then writes the rest. Before the first field is written it refuses
/// (UserError on simulation.output_interval_s) when `outputs` files would not fit in the free
/// space of DIR's file system.
FieldSink field_stream(const std::filesystem::path& dir, const Scenario& scenario,
                       std::size_t outputs);

/// The text of DIR/boundary_heat.csv of a grid run: "time_s,face,heat_flow_w", then for each
/// output time after t = 0 one row per face of the body (sim/grid/body_faces.h: box x_min ...
/// z_max, cylinder top, bottom, side, any other body surface): the heat flowing into the body
/// through that face, averaged over the interval since the previous output time [W]. Summed
/// over the faces and times the interval, it is the energy balance's boundary heat.
std::string format_boundary_heat_csv(const SimulationResult& result);

/// The text of DIR/summary.json (every effective parameter, the events, solver statistics,
/// the final state), as write_simulation_outputs writes it.
std::string summary_json_text(const SimulationResult& result);

/// The first entry of the existing folder `dir` that no thaw command writes into a result folder
/// (interfaces.csv, summary.json, profiles/, fields/, and thaw mesh's mesh/, mesh.partial/ and
/// its temporaries *.tmp-*), or nullopt (also for a missing or empty folder). A result folder is
/// replaced as a whole, so `thaw simulate --out .` in a folder of one's own would delete it.
std::optional<std::string> foreign_entry(const std::filesystem::path& dir);

}  // namespace thaw::sim
