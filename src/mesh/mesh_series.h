#pragma once
// Meshes every step of a simulation folder: reads SIMDIR/interfaces.csv and SIMDIR/summary.json
// (sim/io contract) and writes SIMDIR/mesh/step_NNNNNN_inner.obj, ..._outer.obj and
// manifest.json ("thaw-mesh/1"). Surfaces are meshed in parallel (OpenMP, one independent mesher
// per distinct surface shape: similar surfaces are meshed once and scaled, similar_surface.h);
// the output is byte-identical whatever the number of threads. The folder is filled
// under a temporary name and replaces SIMDIR/mesh only when everything succeeded.
// Knows nothing about CGAL (surface_mesher.h does the meshing) nor about rendering.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "base/progress.h"
#include "sim/format/interface_history.h"
#include "src/mesh/mesh_farm.h"
#include "src/mesh/mesh_options.h"

namespace thaw::mesh {

/// One surface of one step in the manifest.
struct SurfaceRecord {
  std::optional<std::string> file;  ///< OBJ file name relative to SIMDIR/mesh; empty if vanished
  std::string reason;               ///< why there is no file ("" if there is one)
  long triangles = 0;
  double radius_m = 0;          ///< distance of the surface from its core [m]
  double distance_bound_m = 0;  ///< effective CGAL facet_distance used [m]
  double volume_m3 = 0;         ///< enclosed volume of the mesh [m^3]
  double exact_volume_m3 = 0;   ///< enclosed volume of the exact surface [m^3]
};

struct StepRecord {
  long step = 0;
  double time_s = 0, inner_radius_m = 0, outer_radius_m = 0;
  SurfaceRecord inner, outer;
  /// Both surfaces exist and every inner vertex is strictly inside every outer face's plane
  /// (exact test for these convex shapes); nullopt when a surface vanished.
  std::optional<bool> inner_inside_outer;
  /// Grid runs (grid_series.h): sealed cavities, their mean water fraction, and "" or the check
  /// a smoother candidate surface failed (a less even one was written).
  int cavities = 0;
  double cavity_water_fraction = 0;
  std::string remesh_problem;
  double iso_level = 0.5;  ///< grid runs: level of the ice-fraction isosurface (grid_mesher.h)
};

struct MeshManifest {
  /// A grid run (grid_series.h): surfaces from fields/step_NNNNNN.grid, `geometry` unused.
  bool grid = false;
  MeshOptions options;  ///< effective options (after resolve_triangle_target)
  sim::ShellGeometry geometry;
  std::vector<StepRecord> steps;
  /// Thinnest shell (outer - inner) [m] of a step whose inner mesh is strictly inside its outer
  /// mesh; nullopt if no step had both surfaces.
  std::optional<double> thinnest_contained_shell_m;
  /// Steps whose shell was too thin for strict containment at the finest refinement allowed.
  std::vector<long> steps_inner_touching_outer;
  /// Meshes actually made: surfaces that are scaled copies of each other (similar_surface.h)
  /// share one (a sphere series with the default relative distance bound needs only a few).
  long distinct_meshes = 0;
  /// Of those, how many were taken from SIMDIR/mesh.partial/ (kept by an interrupted run)
  /// instead of being meshed again. Not written to the manifest (it would differ on resume).
  long resumed_meshes = 0;
  /// Only some steps were meshed (mesh_simulation_steps): their surface files are in
  /// partial_steps_dir, not SIMDIR/mesh. Not written to the manifest.
  bool partial = false;
};

/// "step_000012_inner.obj" / "step_000012_outer.obj".
std::string surface_file_name(long step, bool inner);

/// Meshes SIMDIR as described above and returns the manifest it wrote; a grid run (a fields/
/// folder) is meshed by mesh_grid_simulation_folder (grid_series.h) into the same layout.
/// `progress` is called with (surfaces done, surfaces total). Throws thaw::UserError (one line
/// naming the file) on a missing or malformed input, an unwritable SIMDIR/mesh, or a surface that
/// failed its checks; nothing is left half-written then (an existing SIMDIR/mesh is kept).
/// `farm` computes the distinct meshes and the surfaces (this process's threads by default); with
/// a farm of several processes every process calls this with the same arguments, `progress` is
/// called on the leader, and only the leader's return value is the manifest (the others return
/// before the checks, which only the leader makes and throws from).
MeshManifest mesh_simulation_folder(const std::filesystem::path& simdir, const MeshOptions& options,
                                    const ProgressCallback& progress = {},
                                    WorkFarm& farm = this_process_farm());

/// For `thaw run --frames`: meshes only the surfaces of the steps at `step_indexes` (positions in
/// interfaces.csv) into partial_steps_dir(simdir), each file atomically, and returns the manifest
/// of every step, the others without files (their reason says why). No SIMDIR/mesh, no
/// manifest.json: the forms are kept in SIMDIR/mesh.partial/ as by an interrupted run, so a later
/// mesh_simulation_folder meshes only the rest and writes the bytes a whole run does (and so do
/// these files). Several processes may do this at once on one folder. A grid run is meshed
/// whole (mesh_simulation_folder). Throws as mesh_simulation_folder; same farm contract.
MeshManifest mesh_simulation_steps(const std::filesystem::path& simdir, const MeshOptions& options,
                                   const std::vector<long>& step_indexes,
                                   const ProgressCallback& progress = {},
                                   WorkFarm& farm = this_process_farm());

/// SIMDIR/mesh.partial/steps: where mesh_simulation_steps writes its surfaces.
std::filesystem::path partial_steps_dir(const std::filesystem::path& simdir);

/// The manifest as written to manifest.json.
nlohmann::ordered_json to_json(const MeshManifest& manifest);

/// Reads the steps of a manifest.json written by mesh_simulation_folder (step, time, radii, the
/// surface files and triangle counts; options and statistics are not read back). Throws
/// thaw::UserError naming the file if it is missing, malformed or not "thaw-mesh/1".
MeshManifest read_mesh_manifest(const std::filesystem::path& manifest_json);

}  // namespace thaw::mesh
