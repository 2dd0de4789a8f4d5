#pragma once
// Hand-off of a grid run's fields as OpenVDB volumes, which Blender and Houdini read natively:
// DIR/handoff/vdb/fields_NNNNNN.vdb, one file per step with three float grids on the solver's own
// cells, `temperature_c` [C] (every cell, the air padding included), and `ice_fraction` and
// `water_fraction` [0, 1] (the cells holding some, background 0). Each grid's transform puts a
// voxel's centre where that cell is in the world, beside the hand-off meshes: voxel size = the
// cell edge [m], index (i, j, k) at origin + (i + 1/2, j + 1/2, k + 1/2) * edge + the step's
// placement offset (handoff_export.h), metres, y up. An axisymmetric run's (r, y) field is first
// revolved about the y axis onto a 3D grid of the same cells (revolved_field). The only code that
// sees OpenVDB (built with THAW_OPENVDB, CMake finds Debian's libopenvdb-dev).
#include <array>
#include <filesystem>
#include <functional>
#include <string>

#include "sim/format/grid_field_file.h"

namespace thaw::pipeline {

/// "fields_000012.vdb".
std::string vdb_file_name(long step);

/// An axisymmetric field (nr x ny cells of edge h, r from the axis) revolved about the y axis onto
/// a cartesian one: 2 nr x ny x 2 nr cells of edge h, x and z in [-nr h, nr h], y as in the field.
/// Each cell takes the values of the ring its centre lies in (ring floor(r / h), r = hypot(x, z)
/// at the centre): the solver's own piecewise-constant values, nothing interpolated. Centres
/// beyond the outermost ring (the corners, r > nr h) take that ring's values: the solver's outer
/// air padding, at the boundary's temperature. A cartesian field is returned unchanged.
sim::GridField revolved_field(const sim::GridField& field);

/// Writes `field` as described above to `path` (atomic: a temporary name, then rename), with the
/// step's time as file metadata "time_s". An axisymmetric field is revolved first.
void write_field_vdb(const std::filesystem::path& path, const sim::GridField& field,
                     const std::array<double, 3>& offset_m);

/// Every SIMDIR/fields/step_NNNNNN.grid of a 3D run into OUT_DIR (created), placed by
/// offset_of(step). Returns the number of files; 0 (nothing written) for 1D runs (no fields).
long write_vdb_sequence(const std::filesystem::path& simdir, const std::filesystem::path& out_dir,
                        const std::function<std::array<double, 3>(long step)>& offset_of);

}  // namespace thaw::pipeline
