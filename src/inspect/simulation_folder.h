#pragma once
// A simulation folder as the inspector sees it: SIMDIR/interfaces.csv (the solver's history),
// optionally SIMDIR/summary.json (geometry) and SIMDIR/mesh/manifest.json with one inner and one
// outer OBJ per step (null when that surface has vanished). Reading validates the contract and
// throws thaw::UserError naming file and entry; inspecting runs inspect_obj on every surface.
// Knows nothing about how the files were produced.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "base/progress.h"
#include "sim/format/interface_history.h"
#include "src/inspect/mesh_report.h"

namespace thaw::inspect {

/// One meshed step from mesh/manifest.json.
struct MeshedStep {
  long step = 0;                               ///< index into interfaces.csv rows
  double time_s = 0;                           ///< simulated time [s]
  double inner_radius_m = 0;                   ///< water|ice front [m]
  double outer_radius_m = 0;                   ///< ice|air surface [m]
  std::optional<std::filesystem::path> inner;  ///< absolute OBJ path; nullopt when vanished
  std::optional<std::filesystem::path> outer;  ///< absolute OBJ path; nullopt when vanished
  /// The mesher's exact solid volumes ("inner_exact_volume_m3" ...) when the manifest has them.
  std::optional<double> inner_exact_volume_m3, outer_exact_volume_m3;
};

struct SimulationFolder {
  std::filesystem::path dir;
  std::vector<sim::InterfaceRecord> rows;      ///< interfaces.csv, one per output time
  std::optional<sim::ShellGeometry> geometry;  ///< from summary.json when present
  bool meshed = false;                         ///< mesh/manifest.json exists
  std::vector<MeshedStep> steps;               ///< manifest steps in file order (empty if !meshed)
};

/// True when `path` is a directory holding interfaces.csv.
bool is_simulation_folder(const std::filesystem::path& path);

/// Reads interfaces.csv (required), summary.json and mesh/manifest.json (both optional).
SimulationFolder read_simulation_folder(const std::filesystem::path& dir);

/// Reads a mesh manifest ({"format":"thaw-mesh/1","steps":[...]}); OBJ names are resolved
/// against the manifest's folder. Times and radii missing from a step come from `rows`.
std::vector<MeshedStep> read_mesh_manifest(const std::filesystem::path& manifest,
                                           const std::vector<sim::InterfaceRecord>& rows);

/// Exact volume of the solid bounded by a surface of radius r [m] for the mesher's shapes:
/// sphere 4/3 pi r^3; cylinder a capsule pi r^2 L + 4/3 pi r^3; nullopt for planar slabs and
/// unknown geometry (no summary.json). [m^3]
std::optional<double> exact_volume_m3(const std::optional<sim::ShellGeometry>& geometry,
                                      double radius_m);

struct StepReport {
  MeshedStep step;
  std::optional<MeshReport> inner, outer;  ///< nullopt when the surface vanished
  /// From the manifest when present, else exact_volume_m3() [m^3].
  std::optional<double> inner_exact_volume_m3, outer_exact_volume_m3;
};

/// Inspects every surface of every meshed step; `progress` gets (steps done, steps total).
std::vector<StepReport> inspect_simulation(const SimulationFolder& folder,
                                           const ProgressCallback& progress = {});

/// JSON array: one object per step with step, time_s, radii, and "inner"/"outer" MeshReport
/// objects (null when vanished) extended with exact_volume_m3 and volume_error_rel.
nlohmann::ordered_json to_json(const std::vector<StepReport>& reports);

/// Human-readable table, one line per step and surface.
std::string format_table(const SimulationFolder& folder, const std::vector<StepReport>& reports);

}  // namespace thaw::inspect
