#pragma once
// Meshes one closed surface (ShellShape) with CGAL 5.5 Mesh_3 on its implicit function, facet
// criteria only, manifold, no perturb / exude, and checks the result with CGAL
// Polygon_mesh_processing before handing it out. This header exposes no CGAL type; its one
// source file is the only place in thaw that instantiates Mesh_3 (a ~34 s, ~3 GB compile).
// Knows nothing about files, steps or threads: one call = one independent mesher, safe to run
// concurrently and deterministic (the domain's random generator is seeded with 0).
#include <memory>
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

/// mesh_surface taken apart for a caller that hands the mesh on before its checks have run (the
/// mesh stage shares a form with other processes at once and checks it while they copy it):
/// mesh() is exactly what mesh_surface returns when check() is "" (mesh_surface = this + check()
/// thrown as MeshError). Keeps CGAL's own surface for check(), so the checks cost what they cost
/// in mesh_surface.
class UncheckedSurface {
 public:
  UncheckedSurface(UncheckedSurface&&) noexcept;
  UncheckedSurface& operator=(UncheckedSurface&&) noexcept;
  ~UncheckedSurface();
  const TriangleMesh& mesh() const { return m_mesh; }
  TriangleMesh take_mesh() { return std::move(m_mesh); }
  /// "" or what mesh_surface's MeshError would say (check_closed_manifold_outward's checks).
  std::string check() const;

 private:
  friend UncheckedSurface mesh_surface_unchecked(const ShellShape&, const SurfaceCriteria&,
                                                 const MeshOptions&);
  struct Cgal;
  UncheckedSurface(std::unique_ptr<Cgal> cgal, TriangleMesh mesh);
  std::unique_ptr<Cgal> m_cgal;
  TriangleMesh m_mesh;
};

/// Mesh_3 and the extraction of mesh_surface, without the checks. Throws MeshError (bad input,
/// CGAL failures).
UncheckedSurface mesh_surface_unchecked(const ShellShape& shape, const SurfaceCriteria& criteria,
                                        const MeshOptions& options);

/// The CGAL Polygon_mesh_processing checks applied to every produced mesh: returns "" when the
/// mesh is closed, 2-manifold, of sphere topology (Euler characteristic 2), free of
/// self-intersections and outward oriented, else a short description of the first failure.
std::string check_closed_manifold_outward(const TriangleMesh& mesh);

}  // namespace thaw::mesh
