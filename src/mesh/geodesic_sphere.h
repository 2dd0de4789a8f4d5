#pragma once
// The sphere's own mesher: a geodesic polyhedron (Buckminster Fuller's class I subdivision: each
// face of the regular icosahedron cut into n^2 triangles by its n-fold barycentric grid, every
// grid point projected onto the sphere), with the least frequency n whose facets meet the facet
// criteria as CGAL Mesh_3 states them (mesh_options.h: smallest angle, radius of the surface
// Delaunay ball, distance from the facet's circumcentre to the surface). A closed form where
// Mesh_3 refines a 3D Delaunay triangulation: a few milliseconds against ~0.1 s for the default
// film's form, and about a quarter fewer triangles for the same distance bound (docs/mesh.md).
// Knows nothing about CGAL, files or threads; deterministic.
#include "src/mesh/mesh_options.h"
#include "src/mesh/triangle_mesh.h"

namespace thaw::mesh {

/// The largest frequency geodesic_frequency considers (20 n^2 = 335 million triangles).
constexpr int kMaxGeodesicFrequency = 4096;

/// The worst facet of frequency n on the sphere of radius r (by symmetry, of one icosahedron
/// face): every facet's vertices lie on the sphere, so its circumcentre is its deepest point and
/// its surface Delaunay ball is centred where the line from the sphere's centre through the
/// circumcentre meets the sphere.
struct GeodesicFacets {
  double max_distance_m = 0;     ///< circumcentre to sphere: r - sqrt(r^2 - R^2), R circumradius
  double max_ball_radius_m = 0;  ///< sqrt(2 r distance) (the ball's radius, Pythagoras)
  double min_angle_deg = 180;
};
GeodesicFacets geodesic_facets(double radius_m, int frequency);

/// The least frequency in [1, kMaxGeodesicFrequency] whose facets meet `criteria` on the sphere
/// of radius `radius_m` (every facet: angle >= facet_angle_deg, ball radius <= facet_size_m,
/// distance <= facet_distance_m); 0 if none does (an angle bound above ~54 degrees, the smallest
/// angle of every frequency above 1, or a distance bound below ~1e-8 r).
int geodesic_frequency(double radius_m, const SurfaceCriteria& criteria);

/// The geodesic mesh of frequency n of the sphere of radius `radius_m` about the origin: 20 n^2
/// triangles, 10 n^2 + 2 vertices, outward, no normals. THAW_CHECK: 1 <= n <=
/// kMaxGeodesicFrequency and radius > 0.
TriangleMesh geodesic_sphere(double radius_m, int frequency);

}  // namespace thaw::mesh
