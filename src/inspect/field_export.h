#pragma once
// The grid solver's fields (sim/io/grid_field.h, DIR/sim/fields/step_NNNNNN.grid) as VTK image
// data for ParaView: one .vti per step with the cell data temperature_c [C], ice_fraction and
// water_fraction [0, 1] on the solver's own cells (origin and spacing in metres; an axisymmetric
// field is the (r, y) half-plane, x = r, one cell thick in z), and a .pvd time series of them
// (timestep = simulated time [s]). Every file is atomic; the .pvd is written last. Needs no
// display.
#include <filesystem>

#include "sim/io/grid_field.h"
#include "src/common/progress.h"

namespace thaw::inspect {

/// Writes `field` as a VTK XML ImageData file (appended raw binary, zlib).
void write_vti(const std::filesystem::path& path, const sim::GridField& field);

/// Writes `out_pvd` and `<stem>_vti/step_NNNNNN.vti` for every SIMDIR/fields/step_*.grid in step
/// order. Returns the number of steps; 0 (and nothing written) if SIMDIR has no fields.
long write_field_series(const std::filesystem::path& simdir, const std::filesystem::path& out_pvd,
                        const ProgressCallback& progress = {});

}  // namespace thaw::inspect
