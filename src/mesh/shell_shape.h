#pragma once
// The exact closed surfaces the mesher approximates, as signed distance functions (no CGAL).
// Every surface is the boundary of the set of points within `radius_m` of a convex core:
//   sphere   core = the origin                          -> a sphere of radius r
//   cylinder core = the segment |z| <= L/2 on the z axis -> a capsule: tube of length L along z
//                                                          with hemispherical ends of radius r
//   planar   core = the square x = 0, |y|,|z| <= S/2     -> a slab |x| <= r with flat S x S faces
//                                                          and edges rounded with radius r
// Inner (water|ice) and outer (ice|air) surfaces share the core, so the shell between them has
// the uniform thickness outer - inner everywhere and stays closed and smooth.
// Knows nothing about CGAL, files or options.
#include <array>

#include "sim/format/interface_history.h"

namespace thaw::mesh {

using Vec3 = std::array<double, 3>;

struct ShellShape {
  sim::Geometry geometry = sim::Geometry::sphere;
  /// Distance of the surface from its core [m]: sphere/capsule radius, slab half-thickness.
  double radius_m = 0;
  /// Capsule: half the tube length L/2 [m]; slab: half the lateral size S/2 [m]; sphere: 0.
  double core_half_size_m = 0;

  /// Builds the surface at `radius_m` for a shell geometry read from summary.json.
  static ShellShape from_geometry(const sim::ShellGeometry& geometry, double radius_m);

  /// Point of the core nearest to p [m].
  Vec3 closest_core_point(const Vec3& p) const;
  /// Signed distance to the surface [m], negative inside (exact for these shapes).
  double signed_distance(const Vec3& p) const;
  /// Unit outward normal at (or the gradient of the distance through) p; p must not be on the core.
  Vec3 outward_normal(const Vec3& p) const;
  /// Support function of the core, max over core points c of n . c [m], n a unit vector.
  /// The surface's support function is core_support(n) + radius_m (Minkowski sum with a ball).
  double core_support(const Vec3& n) const;
  /// Exact enclosed volume [m^3] (Steiner formula for a convex core plus a ball).
  double volume() const;
  /// Exact surface area [m^2].
  double area() const;
  /// Radius of a sphere about the origin that contains the surface [m].
  double bounding_radius() const;
  /// Length the relative distance bound is taken of [m]: the radius for sphere and capsule
  /// (their volume error goes as distance / radius), half the lateral size for the slab (its
  /// curved rim is a small part of it: the volume error goes as pi * distance / S).
  double accuracy_length() const;
};

}  // namespace thaw::mesh
