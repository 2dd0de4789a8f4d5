#pragma once
// The output contract of axisymmetric and 3D runs: one output time's cell-centred fields on a
// uniform grid of cubic cells (DIR/fields/step_NNNNNN.grid), written by the grid solver and read
// by the mesher and the pipeline. Binary, little-endian, with a versioned header and a checksum
// so that a truncated or damaged file is refused instead of meshed. Knows nothing of the solver.
#include <filesystem>

#include "sim/grid/grid_field.h"

namespace thaw::sim {

/// Writes `f` atomically (base/atomic_file.h): header "THAWGRID", format version, geometry,
/// cells, origin, spacing, time, then the three float arrays, (version 2 only) the velocity's
/// 3 floats per cell, and an FNV-1a checksum. A field without velocity is written as version 1,
/// byte for byte what thaw wrote before velocities were kept; one with velocity as version 2.
/// THAW_CHECK that the arrays have cell_count() entries (3 x for the velocity).
void write_grid_field(const std::filesystem::path& file, const GridField& f);
/// Reads a file written by write_grid_field; throws thaw::UserError naming the file on any
/// corruption (missing, truncated, wrong magic or version, bad sizes, checksum mismatch,
/// trailing bytes, non-finite values, fractions outside [0, 1] or summing above 1, a velocity
/// faster than kMaxFieldSpeedM_S). Reads versions 1 (no velocity: velocity_m_s empty) and 2.
GridField read_grid_field(const std::filesystem::path& file);

/// The fastest velocity a field file may hold [m/s]: far above any buoyant flow in a body the
/// scenario rules accept (free fall over 100 m reaches 45 m/s), far below float's overflow.
constexpr double kMaxFieldSpeedM_S = 1e3;

}  // namespace thaw::sim
