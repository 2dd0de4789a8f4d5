#pragma once
// A simulation's result folder, written from a SimulationResult (sim/simulate.h): interfaces.csv,
// summary.json (every effective parameter, events, solver statistics) and profiles/step_NNNNNN.csv
// for the 1D geometries or fields/step_NNNNNN.grid for the grid ones. The sim's file-format
// layer: the solver core never sees these formats.
#include <filesystem>

#include "sim/simulate.h"

namespace thaw::sim {

/// Writes interfaces.csv, profiles/step_NNNNNN.csv and summary.json into `dir` (which must
/// exist; use a thaw::StagingDirectory for an all-or-nothing result folder).
void write_simulation_outputs(const std::filesystem::path& dir, const SimulationResult& result);

}  // namespace thaw::sim
