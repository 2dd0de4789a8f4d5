#pragma once
// Meshes every step of a grid (axisymmetric or 3D) simulation folder: SIMDIR/interfaces.csv lists
// the steps, SIMDIR/fields/step_NNNNNN.grid holds each step's field (sim/format/grid_field_file.h).
// Writes the same SIMDIR/mesh/ as the 1D series (mesh_series.h: step_NNNNNN_outer.obj, _inner.obj,
// manifest.json "thaw-mesh/1"), so the pipeline, the renderer and `thaw inspect` read both alike.
// Steps are meshed in parallel (OpenMP, one grid mesher per step), byte-identical for any thread
// count; the folder is staged and replaces SIMDIR/mesh only when every step succeeded.
// Knows nothing about CGAL nor rendering.
#include <filesystem>
#include <string>

#include "base/progress.h"
#include "src/mesh/grid_mesher.h"
#include "src/mesh/mesh_options.h"
#include "src/mesh/mesh_series.h"

namespace thaw::mesh {

/// SIMDIR/fields/step_000012.grid.
std::filesystem::path grid_field_file(const std::filesystem::path& simdir, long step);

/// The grid mesher's options of a run's [mesh] options: of these only edge_length_m (0 = the
/// field's cell edge) and normals reach a grid field; the CGAL facet criteria of the 1D shapes do
/// not. The one conversion for the series below and for `thaw gui`'s t = 0 preview.
GridMeshOptions grid_mesh_options(const MeshOptions& options);

/// True when SIMDIR holds a grid run (a fields/ folder with step_*.grid files).
bool is_grid_simulation_folder(const std::filesystem::path& simdir);

/// Meshes the grid run in SIMDIR (see above). Of `options`, edge_length_m (0 = each field's cell
/// edge), normals and jobs apply; the CGAL facet criteria of the 1D shapes do not. Throws
/// thaw::UserError naming the file on a missing or damaged field, or a surface that failed its
/// checks; nothing is left half-written.
/// `farm` as for mesh_simulation_folder (mesh_series.h): one item per step.
MeshManifest mesh_grid_simulation_folder(const std::filesystem::path& simdir,
                                         const MeshOptions& options,
                                         const ProgressCallback& progress = {},
                                         WorkFarm& farm = this_process_farm());

}  // namespace thaw::mesh
