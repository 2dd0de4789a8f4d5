#pragma once
// The output contract of axisymmetric and 3D runs: one output time's cell-centred fields on a
// uniform grid of cubic cells (DIR/fields/step_NNNNNN.grid), written by the grid solver and read
// by the mesher and the pipeline. Binary, little-endian, with a versioned header and a checksum
// so that a truncated or damaged file is refused instead of meshed. Knows nothing of the solver.
#include <filesystem>

#include "sim/grid/grid_field.h"

namespace thaw::sim {

/// Writes `f` atomically (base/atomic_file.h): header "THAWGRID", format version, geometry,
/// cells, origin, spacing, time, then the three float arrays and an FNV-1a checksum. THAW_CHECK
/// that the arrays have cell_count() entries (a programming error otherwise).
void write_grid_field(const std::filesystem::path& file, const GridField& f);
/// Reads a file written by write_grid_field; throws thaw::UserError naming the file on any
/// corruption (missing, truncated, wrong magic or version, bad sizes, checksum mismatch,
/// trailing bytes, non-finite values, fractions outside [0, 1] or summing above 1).
GridField read_grid_field(const std::filesystem::path& file);

}  // namespace thaw::sim
