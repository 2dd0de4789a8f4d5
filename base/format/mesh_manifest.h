#pragma once
// The one reader of `thaw-mesh/1` manifests (DIR/mesh/manifest.json, written by src/mesh): what
// every meshed step holds, checked strictly. Each problem is a thaw::UserError naming the file
// and the JSON key ("steps[3].time_s") in plain words, never the JSON library's exception text.
// Cross-checks against interfaces.csv belong to the callers. Knows nothing about CGAL or VTK.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace thaw::meshio {

/// The format tag this reader accepts.
inline constexpr const char* kMeshManifestFormat = "thaw-mesh/1";

struct ManifestStep {
  long step = 0;              ///< row of interfaces.csv (>= 0, increasing)
  double time_s = 0;          ///< simulated time [s]
  double inner_radius_m = 0;  ///< water|ice front [m] (volume-equivalent on grid runs)
  double outer_radius_m = 0;  ///< ice surface [m]
  /// Surface files, plain names in the manifest's folder; nullopt when the surface vanished.
  std::optional<std::string> inner, outer;
  long inner_triangles = 0, outer_triangles = 0;
  std::optional<double> inner_exact_volume_m3, outer_exact_volume_m3;
};

struct MeshManifestFile {
  /// geometry.geometry: "sphere", "cylinder", "planar" or "grid".
  std::string geometry;
  double length_m = 0;        ///< geometry.length_m (cylinder), else 0
  double lateral_size_m = 0;  ///< geometry.lateral_size_m (planar), else 0
  bool planar_symmetric = false;
  std::vector<ManifestStep> steps;
};

/// Reads and checks a manifest: missing or unreadable file, malformed JSON, wrong format tag,
/// a missing or mistyped key, a negative or non-finite number, steps not increasing, a surface
/// name that is not a plain file name.
MeshManifestFile read_mesh_manifest(const std::filesystem::path& manifest_json);

/// Same on text; `source_name` stands for the file name in messages.
MeshManifestFile parse_mesh_manifest(const std::string& text, const std::string& source_name);

}  // namespace thaw::meshio
