#pragma once
// Options of the surface mesher, with defaults tuned for 640x640 renders of a shell a few
// centimetres across (docs/mesh.md has the trade-off), and the per-surface CGAL criteria derived
// from them. No CGAL here; the criteria are plain numbers.
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "src/mesh/shell_shape.h"

namespace thaw::mesh {

struct MeshOptions {
  /// Target triangle edge length where the surface is flat or gently curved [m]
  /// (CGAL facet_size = edge / sqrt(3), the circumradius of an equilateral triangle).
  /// 0 = auto: scene radius / 12 (2.5 mm for a 3 cm shell).
  double edge_length_m = 0;
  /// If > 0: replaces edge_length_m by the edge length that gives the largest surface of the
  /// series about this many triangles; distance bounds not given explicitly are then relaxed so
  /// that they do not add triangles (see resolve_triangle_target).
  long triangles = 0;
  /// Lower bound on triangle angles [deg], CGAL facet_angle; (0, 30] (30 guarantees termination).
  double angle_deg = 30;
  /// Upper bound on the distance between a triangle and the true surface [m], CGAL facet_distance.
  /// 0 = auto: 1e-3 x scene radius (30 um for a 3 cm shell: a quarter pixel when a 640 x 640
  /// render frames the whole shell).
  double distance_m = 0;
  /// Radius of a sphere about the origin holding every surface of the series [m], the scale of
  /// the automatic edge length and distance; 0 = each surface's own bounding radius.
  /// mesh_simulation_folder sets it from the largest outer surface.
  double scene_radius_m = 0;
  /// The distance bound is also at most this fraction of the surface's accuracy length
  /// (ShellShape::accuracy_length), so small surfaces keep their relative volume accuracy.
  double relative_distance = 1e-3;
  /// Surfaces closer than this to their core (sphere or capsule radius, slab half-thickness)
  /// are not meshed and are recorded as vanished [m]: at 30 um a 3 cm shell's render shows
  /// them as a fraction of a pixel, and thinner slabs cost Mesh_3 (S / r)^2 triangles.
  double min_radius_m = 3e-5;
  /// Per-surface triangle budget (0 = none): where the distance bounds would need more
  /// triangles (thin capsules, thin slabs: the count grows as 1 / distance), the distance bound
  /// of that surface is relaxed until the estimate fits, and the manifest records the bound used.
  long max_triangles = 60'000;
  /// Write vertex normals (`vn`, gradient of the implicit function) into the OBJ files.
  bool normals = true;
  /// Worker threads for a series (one mesher per surface); 0 = all available cores.
  int jobs = 0;
  /// CGAL relative_error_bound of the surface intersection search (vertex placement accuracy
  /// relative to the bounding box); the CGAL default 1e-3 leaves visible vertex noise.
  double relative_error_bound = 1e-6;
  /// With a triangle target: keep distance_m / relative_distance as given instead of relaxing
  /// them (the CLI sets this when --distance or --relative-distance is given explicitly).
  bool keep_distance = false;
  /// Mesh surfaces that are scaled copies of each other once and scale the mesh
  /// (similar_surface.h); false meshes every surface on its own (for benchmarks: same criteria).
  bool reuse_similar = true;
  /// Set by resolve_triangle_target: the distance bounds were relaxed for a triangle target.
  bool distance_relaxed = false;
};

/// Most triangles one surface may have: the limit of `triangles` and of what the criteria may
/// ask for (check_triangle_count). A typo such as an edge of 1e-6 m on a 3 cm shell asked for
/// ~1e10 and ran for ever; Mesh_3 needs gigabytes at this limit already.
inline constexpr double kMaxTrianglesPerSurface = 5e7;
/// Shortest accepted edge_length_m (0 = automatic) [m]: a hundredth of the shortest shell the
/// solver accepts (1e-4 m).
inline constexpr double kMinEdgeLengthM = 1e-6;

/// Throws thaw::UserError (file "", where = option name) for a non-finite or out-of-range option.
void validate(const MeshOptions& options);

/// Returns options with scene_radius_m set and the automatic (0) edge length and distance
/// replaced by their values for that scene radius [m].
MeshOptions resolve_scene(MeshOptions options, double scene_radius_m);

/// If options.triangles > 0, returns options with edge_length_m set so that a surface of area
/// `largest_area_m2` gets about `triangles` triangles (Delaunay surface meshes with facet_angle 30
/// have about 1.32 A / facet_size^2 triangles, measured on spheres: 16.6 (R / facet_size)^2),
/// and, unless options.keep_distance, the distance bounds relaxed to values that do not bind.
/// Otherwise returns options unchanged.
MeshOptions resolve_triangle_target(MeshOptions options, double largest_area_m2);

/// The CGAL facet criteria for one surface.
struct SurfaceCriteria {
  double facet_angle_deg = 30;
  double facet_size_m = 0;      ///< radius of the surface Delaunay balls [m]
  double facet_distance_m = 0;  ///< distance of facet circumcentres to the surface [m]
};

/// Automatic values (0) are taken for the scene radius, or the shape's bounding radius if that
/// is 0 too. facet_size = edge / sqrt(3); facet_distance = min(distance_m, relative_distance *
/// shape.accuracy_length()), further capped at `max_distance_m` (> 0: used to keep an outer
/// surface's triangles off the inner surface), then relaxed (multiplied by 1.25 until it fits)
/// if estimate_triangles exceeds options.max_triangles.
SurfaceCriteria criteria_for(const ShellShape& shape, const MeshOptions& options,
                             double max_distance_m = 0);

/// Estimated triangle count of a Mesh_3 surface mesh of `shape` under `criteria`: 1.32 A / r^2
/// per part of area A, with r = min(facet_size, sqrt(2 rho facet_distance)) on a part of
/// curvature radius rho (the circumradius whose sagitta is the distance bound) and, on a slab's
/// flat faces, r = min(facet_size, 2 half-thickness) (Delaunay refinement of a thin plate needs
/// a spacing of about its thickness; measured). Within ~25 % on the shapes here.
double estimate_triangles(const ShellShape& shape, const SurfaceCriteria& criteria);

/// Throws thaw::UserError naming edge_length_m (or distance_m when the size bound alone would
/// fit) when `criteria` would give `shape` more than kMaxTrianglesPerSurface triangles.
void check_triangle_count(const ShellShape& shape, const SurfaceCriteria& criteria);

/// True when even with no distance bound a slab surface would exceed options.max_triangles
/// (a plate too thin for its lateral size); such surfaces are recorded, not meshed.
bool too_thin_to_mesh(const ShellShape& shape, const MeshOptions& options);

/// The effective options as JSON (written into manifest.json; STYLE 7).
nlohmann::ordered_json to_json(const MeshOptions& options);
/// One line of effective options for the terminal.
std::string describe(const MeshOptions& options);

}  // namespace thaw::mesh
