#pragma once
// What `thaw inspect` says about one triangle surface: counts, topology (boundary and non-manifold
// edges, orientation), size (volume, area, bounding box) and element quality (angles, aspect
// ratio). Topology by linear-time edge hashing (base/edge_topology.h), size and quality with
// VTK (vtkMassProperties, vtkMeshQuality), duplicated vertices and degenerate faces counted here.
// The mesh is inspected as given: nothing is merged or repaired first. Needs no display.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "src/inspect/triangle_mesh.h"

namespace thaw::inspect {

struct MeshReport {
  std::string source;                   ///< file name (or a label) the mesh came from
  std::int64_t vertices = 0;            ///< vertex records in the file
  std::int64_t triangles = 0;           ///< triangles (polygons counted after fan splitting)
  std::int64_t edges = 0;               ///< distinct undirected edges (by vertex index)
  std::int64_t boundary_edges = 0;      ///< edges used by exactly one triangle (holes)
  std::int64_t non_manifold_edges = 0;  ///< edges used by three or more triangles
  /// Manifold edges whose two triangles traverse it in the same direction (one of them flipped).
  std::int64_t inconsistent_edges = 0;
  std::int64_t duplicate_vertices = 0;    ///< vertex records whose position repeats an earlier one
  std::int64_t unused_vertices = 0;       ///< vertex records no triangle refers to
  std::int64_t degenerate_triangles = 0;  ///< repeated corner index or (numerically) zero area
  std::int64_t components = 0;            ///< edge-connected pieces of the surface
  std::int64_t euler_characteristic = 0;  ///< V - E + F over used vertices (2 for a sphere)
  bool closed = false;                    ///< no boundary and no non-manifold edge
  bool consistently_oriented = false;     ///< inconsistent_edges == 0
  /// Closed and consistently oriented with positive signed volume (normals point outward);
  /// nullopt when orientation is not defined (open or inconsistent surface).
  std::optional<bool> outward;
  double volume_m3 = 0;  ///< enclosed volume from vtkMassProperties [m^3] (closed only meaningful)
  double signed_volume_m3 = 0;  ///< (1/6) sum a.(b x c) over triangles [m^3]; > 0 when outward
  double area_m2 = 0;           ///< total surface area [m^2]
  std::array<double, 3> bbox_min{}, bbox_max{};  ///< axis-aligned bounding box of used vertices [m]
  double min_edge_m = 0, mean_edge_m = 0, max_edge_m = 0;  ///< edge lengths [m]
  /// Triangle angles over non-degenerate triangles [degrees]: smallest angle anywhere, mean of
  /// each triangle's smallest angle (60 for equilateral triangles), largest angle anywhere.
  double min_angle_deg = 0, mean_min_angle_deg = 0, max_angle_deg = 0;
  /// Verdict aspect ratio L_max (a + b + c) / (4 sqrt(3) A), 1 for an equilateral triangle,
  /// over non-degenerate triangles.
  double mean_aspect_ratio = 0, max_aspect_ratio = 0;
};

/// Inspects an OBJ file (validated by read_obj first; throws thaw::UserError on bad input).
MeshReport inspect_obj(const std::filesystem::path& path);

/// Inspects a mesh already in memory; `source` labels it in the report.
MeshReport inspect_mesh(const TriangleMesh& mesh, const std::string& source);

/// The report as a JSON object with keys vertices, triangles, boundary_edges, non_manifold_edges,
/// volume_m3, area_m2, min_angle_deg, max_aspect_ratio and the rest of MeshReport's fields.
nlohmann::ordered_json to_json(const MeshReport& report);

/// A human-readable multi-line table (ends with a newline).
std::string format_table(const MeshReport& report);

}  // namespace thaw::inspect
