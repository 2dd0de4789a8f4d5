#pragma once
// Isotropic remeshing of a closed triangle surface to a target edge length (CGAL
// Polygon_mesh_processing::isotropic_remeshing: split long / collapse short edges, flip to
// valence 6, tangential relaxation, every vertex projected back onto the input surface), and the
// checks that every surface handed to the renderer passes. Used on marching-tetrahedra surfaces
// (grid_surface.h), whose triangles are as uneven as the lattice crossings. Exposes no CGAL type.
#include <string>

#include "src/mesh/triangle_mesh.h"

namespace thaw::mesh {

/// `mesh` (closed, 2-manifold, consistently oriented; any number of components) remeshed to edges
/// of about `target_edge_m` (CGAL keeps them within [4/5, 4/3] of it) with `iterations` passes;
/// normals are dropped. Not checked here: the caller checks what it finally uses. Returns an
/// empty mesh if `mesh` is not a polygon mesh.
TriangleMesh remesh_isotropic(const TriangleMesh& mesh, double target_edge_m, int iterations);

/// "" when `mesh` is a valid closed 2-manifold triangle surface (any number of components, any
/// genus), consistently oriented with every component enclosing a positive volume (outward),
/// and free of self-intersections; else the first failure.
std::string check_closed_oriented_components(const TriangleMesh& mesh);

}  // namespace thaw::mesh
