// Tests of similar_surface (src/mesh/similar_surface.h): which surfaces may share one mesh up to
// scale. Only exact similarity may share: a cylinder whose radius changes at fixed length is not
// a scaled copy, and neither is a sphere whose absolute size bound binds.
#include "src/mesh/similar_surface.h"

#include <gtest/gtest.h>

#include <cmath>

namespace thaw::mesh {
namespace {

ShellShape shape(sim::Geometry g, double radius_m, double core_half_m) {
  ShellShape s;
  s.geometry = g;
  s.radius_m = radius_m;
  s.core_half_size_m = core_half_m;
  return s;
}

SurfaceCriteria criteria(double size_m, double distance_m) {
  SurfaceCriteria c;
  c.facet_size_m = size_m;
  c.facet_distance_m = distance_m;
  return c;
}

TEST(SimilarSurface, SpheresWithRelativeDistanceShareOneForm) {
  // The defaults of a 3 cm series: size 2.5 mm / sqrt 3, distance 1e-3 x radius. On a sphere of
  // radius r the distance bound d allows Delaunay balls up to sqrt(2 d r) = 0.0447 r <= 1.34 mm
  // < 1.44 mm for r <= 3 cm, so the size bound is redundant and every radius is the unit form.
  const double size = 0.0025 / std::sqrt(3.0);
  const SimilarSurface a =
      similar_surface(shape(sim::Geometry::sphere, 0.03, 0), criteria(size, 1e-3 * 0.03));
  for (double r : {0.0291, 0.02, 0.0137, 0.003, 3e-5}) {
    const SimilarSurface b =
        similar_surface(shape(sim::Geometry::sphere, r, 0), criteria(size, 1e-3 * r));
    EXPECT_EQ(a.key(), b.key()) << r;
    EXPECT_EQ(b.scale_m, r);
    EXPECT_EQ(b.unit_shape.radius_m, 1.0);
  }
  EXPECT_EQ(a.unit_criteria.facet_distance_m, 1e-3);
  EXPECT_EQ(a.unit_criteria.facet_size_m, 2.0);  // redundant bound made canonical
}

TEST(SimilarSurface, BindingSizeBoundKeepsSpheresApart) {
  // At r = 7 cm sqrt(2 d r) = 3.1 mm exceeds the 1.44 mm size bound: the size bound binds, so
  // 7 cm and 8 cm spheres are meshed at different relative resolutions and must not share.
  const double size = 0.0025 / std::sqrt(3.0);
  const SimilarSurface a =
      similar_surface(shape(sim::Geometry::sphere, 0.07, 0), criteria(size, 7e-5));
  const SimilarSurface b =
      similar_surface(shape(sim::Geometry::sphere, 0.08, 0), criteria(size, 8e-5));
  EXPECT_NE(a.key(), b.key());
  EXPECT_NEAR(a.unit_criteria.facet_size_m, size / 0.07, 1e-12);
}

TEST(SimilarSurface, CapsulesShareOnlyWhenExactlyScaled) {
  const SurfaceCriteria c = criteria(0.001, 2e-5);
  const SimilarSurface a = similar_surface(shape(sim::Geometry::cylinder, 0.02, 0.03), c);
  // Same length, smaller radius: a different shape (tube longer relative to its radius).
  const SimilarSurface b =
      similar_surface(shape(sim::Geometry::cylinder, 0.01, 0.03), criteria(0.001, 1e-5));
  EXPECT_NE(a.key(), b.key());
  // Everything halved (shape and bounds): a scaled copy.
  const SimilarSurface h =
      similar_surface(shape(sim::Geometry::cylinder, 0.01, 0.015), criteria(0.0005, 1e-5));
  EXPECT_EQ(a.key(), h.key());
  // The same radius again (a surface that did not move between steps): the same mesh.
  EXPECT_EQ(a.key(), similar_surface(shape(sim::Geometry::cylinder, 0.02, 0.03), c).key());
  // A slab is never a capsule, whatever the numbers.
  EXPECT_NE(a.key(), similar_surface(shape(sim::Geometry::planar, 0.02, 0.03), c).key());
}

TEST(SimilarSurface, CapsuleSizeBoundIsNeverMadeCanonical) {
  // The sphere argument does not hold on a tube (flat along its axis): the size bound binds there.
  const SimilarSurface a =
      similar_surface(shape(sim::Geometry::cylinder, 0.02, 0.03), criteria(0.001, 2e-5));
  EXPECT_NEAR(a.unit_criteria.facet_size_m, 0.05, 1e-15);
}

}  // namespace
}  // namespace thaw::mesh
