#pragma once
// The grid solver's fields (sim/format/grid_field_file.h, DIR/sim/fields/step_NNNNNN.grid) as VTK
// image data for ParaView: one .vti per step with the cell data temperature_c [C], ice_fraction and
// water_fraction [0, 1] and, from runs with flow, the 3-component velocity_m_s [m/s] (the active
// vectors; axisymmetric: (u_r, u_y, 0)) on the solver's own cells (origin and spacing in metres; an
// axisymmetric field is the (r, y) half-plane, x = r, one cell thick in z), and a .pvd time series
// of them (timestep = simulated time [s]), placed like the surfaces of meshes.pvd (pvd_writer.h's
// StepPlacement) so that ParaView shows the fields inside them. Every file is atomic; the .pvd is
// written last. Needs no display.
#include <array>
#include <filesystem>

#include "base/progress.h"
#include "sim/format/grid_field_file.h"
#include "src/inspect/pvd_writer.h"

namespace thaw::inspect {

/// Writes `field` as a VTK XML ImageData file (each array inline, base64 of zlib), its origin
/// moved by `offset_m`.
void write_vti(const std::filesystem::path& path, const sim::GridField& field,
               const std::array<double, 3>& offset_m = {0, 0, 0});

/// Writes `out_pvd` and `<stem>_vti/step_NNNNNN.vti` for every SIMDIR/fields/step_*.grid in step
/// order, step NNNNNN moved by placement(NNNNNN) (none: the solver's frame). Returns the number of
/// steps; 0 (and nothing written) if SIMDIR has no fields.
long write_field_series(const std::filesystem::path& simdir, const std::filesystem::path& out_pvd,
                        const ProgressCallback& progress = {}, const StepPlacement& placement = {});

}  // namespace thaw::inspect
