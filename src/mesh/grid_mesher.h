#pragma once
// Meshes the ice body of one GridField (an axisymmetric or 3D step): node lattice
// (node_lattice.h) -> marching tetrahedra and classification (grid_surface.h) -> isotropic
// remeshing to the requested edge length (surface_remesher.h) -> Taubin smoothing
// (taubin_smoothing.h) -> checks (closed, 2-manifold, outward per component, no
// self-intersection) -> angle-weighted vertex normals of the smoothed surface. Should the remeshed
// or smoothed surface fail a check, the marching-tetrahedra surface (valid by construction) is used
// instead. One call = one independent mesher (safe to run concurrently, deterministic). Knows
// nothing about files.
#include <string>

#include "sim/format/grid_field_file.h"
#include "src/mesh/triangle_mesh.h"

namespace thaw::mesh {

struct GridMeshOptions {
  /// Target triangle edge [m]; 0 = the field's cell edge (finer cannot show more of the field).
  double edge_length_m = 0;
  /// Passes of the [1 2 1] / 4 filter on the ice fraction before extraction (node_lattice.h).
  /// Off by default: it moves curved interfaces inwards (sphere -0.64 % volume at R = 20 h);
  /// Taubin smoothing of the surface removes the bumps instead (docs/mesh.md).
  int smoothing_passes = 0;
  /// Passes of isotropic remeshing; 0 keeps the marching-tetrahedra triangles.
  int remesh_iterations = 3;
  /// Passes of Taubin smoothing of the remeshed surface (taubin_smoothing.h).
  int taubin_passes = 10;
  /// With edges of two cells or more, extract from the 2 x 2 x 2 block average of the field
  /// (grid_mesher.cpp; the volumes are unchanged, the marching-tetrahedra surface 4x smaller).
  bool coarsen = true;
  /// Lower the isosurface level below 1/2 where that level loses more ice than its
  /// interpolation error allows (thin walls of partly melted cells; grid_mesher.cpp).
  bool match_field_volume = true;
  /// Angle-weighted vertex normals (of the smoothed surface: the raw fractions' gradient is
  /// noisy at the cell scale and made sparkles in refraction).
  bool normals = true;
};

struct GridMeshResult {
  TriangleMesh outer;  ///< ice | outside, outward from the ice (empty: no ice)
  TriangleMesh inner;  ///< cavity | ice, outward from the cavity (empty: no sealed cavity)
  int cavities = 0;
  /// Level of the ice-fraction isosurface used (1/2 unless lowered to keep thin walls).
  double iso_level = 0.5;
  double cavity_water_fraction = 0;  ///< mean water fraction in the cavities
  /// "" or the first check a candidate surface failed (the next one, less even, was used).
  std::string remesh_problem;
};

/// Volume of cell (i, j, k) of `field` [m^3]: h^3, or the ring pi (2i + 1) h^3 (axisymmetric).
double cell_volume_m3(const sim::GridField& field, int i);

/// The 2 x 2 x 2 (axisymmetric: 2 x 2 rings) block average of `field`, volume-weighted: an exact
/// volume-fraction field with twice the cell edge holding the same ice and water volumes.
sim::GridField coarsened_twice(const sim::GridField& field);

/// Throws MeshError (surface_mesher.h) if a produced surface fails its checks.
GridMeshResult mesh_grid_field(const sim::GridField& field, const GridMeshOptions& options);

}  // namespace thaw::mesh
