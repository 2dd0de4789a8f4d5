#pragma once
// Scenario ([shape], materials, initial temperatures, outer boundary) -> GridProblem: a grid
// padded with air around the outer body, each cell's ice and water volume fractions by
// sub-sampling the shapes' signed distances, and its enthalpy. Knows nothing of TOML or the solver.
#include "sim/grid/grid_problem.h"
#include "sim/scenario/scenario.h"

namespace thaw::sim {

/// Air cells around the outer body on every open side.
constexpr int kAirPaddingCells = 2;

/// `scenario` must be a valid grid scenario (find_grid_problem); THAW_CHECK otherwise.
GridProblem build_grid_problem(const Scenario& scenario);

/// Initial ice and water volume fractions of every cell of `problem`'s grid (GridField order).
void shape_fractions(const Scenario& scenario, const GridProblem& grid, std::vector<double>& ice,
                     std::vector<double>& water);

}  // namespace thaw::sim
