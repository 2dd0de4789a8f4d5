#pragma once
// Meshes one closed surface (ShellShape) with CGAL 5.5 Mesh_3 on its implicit function, facet
// criteria only, manifold, no perturb / exude, and checks the result with CGAL
// Polygon_mesh_processing before handing it out. This header exposes no CGAL type; its one
// source file is the only place in thaw that instantiates Mesh_3 (a ~34 s, ~3 GB compile).
// Knows nothing about files, steps or threads: one call = one independent mesher, safe to run
// concurrently and deterministic (the domain's random generator is seeded with 0).
#include <stdexcept>
#include <string>

#include "src/mesh/mesh_options.h"
#include "src/mesh/shell_shape.h"
#include "src/mesh/triangle_mesh.h"

namespace thaw::mesh {

/// A produced mesh failed a check (not closed, not 2-manifold, not a sphere topologically,
/// self-intersecting, not outward) or CGAL failed; what() says which.
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Meshes `shape` with the given criteria. Vertices lie on the surface to within
/// options.relative_error_bound times the bounding-box size; normals are filled (outward
/// gradient of the signed distance) when options.normals. Throws MeshError.
TriangleMesh mesh_surface(const ShellShape& shape, const SurfaceCriteria& criteria,
                          const MeshOptions& options);
/// Same with criteria_for(shape, options).
TriangleMesh mesh_surface(const ShellShape& shape, const MeshOptions& options);

/// The CGAL Polygon_mesh_processing checks applied to every produced mesh: returns "" when the
/// mesh is closed, 2-manifold, of sphere topology (Euler characteristic 2), free of
/// self-intersections and outward oriented, else a short description of the first failure.
std::string check_closed_manifold_outward(const TriangleMesh& mesh);

}  // namespace thaw::mesh
