#pragma once
// Reuse of one mesh for similar surfaces: the canonical form of a surface and its meshing
// criteria up to scale. Mesh_3 on a shape scaled by s with every length criterion scaled by s
// (the angle bound and the relative placement error are scale-free) is the same algorithm on the
// same problem, so the unit-scale mesh scaled by s meets exactly the criteria of the original.
// Two surfaces are meshed once when their canonical forms are equal: a sphere of any radius is
// the unit sphere scaled; a capsule or slab is a scaled copy only if core_half_size / radius is
// the same (a cylinder whose radius shrinks at fixed length is NOT similar to the first one).
// Knows nothing about CGAL, files or threads.
#include <tuple>

#include "src/mesh/mesh_options.h"
#include "src/mesh/shell_shape.h"

namespace thaw::mesh {

struct SimilarSurface {
  /// The shape at unit radius (radius_m = 1, core_half_size_m = original ratio).
  ShellShape unit_shape;
  /// The criteria of the original divided by its radius.
  SurfaceCriteria unit_criteria;
  /// Length the unit mesh is multiplied by to give the original [m] (the original radius).
  double scale_m = 1;

  /// Equal when the two canonical forms are (geometry, core ratio, criteria): the meshes are
  /// interchangeable up to scale.
  auto key() const {
    return std::tuple(static_cast<int>(unit_shape.geometry), unit_shape.core_half_size_m,
                      unit_criteria.facet_angle_deg, unit_criteria.facet_size_m,
                      unit_criteria.facet_distance_m);
  }
};

/// The canonical form of meshing `shape` (radius > 0) with `criteria`. Ratios are rounded to 12
/// significant digits (a relative change <= 5e-13 of a bound, far below the 1e-6 vertex placement
/// error) so that e.g. (1e-3 r) / r compares equal for every r. On a sphere the size bound is
/// made canonical when the distance bound implies it (see the .cpp), which makes every sphere
/// whose distance bound is relative (the default) the same unit mesh.
SimilarSurface similar_surface(const ShellShape& shape, const SurfaceCriteria& criteria);

}  // namespace thaw::mesh
