#include "src/mesh/similar_surface.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "base/check.h"

namespace thaw::mesh {

namespace {
double round12(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.12g", x);
  return std::strtod(buf, nullptr);
}
}  // namespace

SimilarSurface similar_surface(const ShellShape& shape, const SurfaceCriteria& c) {
  THAW_CHECK(shape.radius_m > 0 && std::isfinite(shape.radius_m),
             "surface radius must be finite and > 0");
  const double r = shape.radius_m;
  SimilarSurface s;
  s.scale_m = r;
  s.unit_shape = shape;
  s.unit_shape.radius_m = 1;
  s.unit_shape.core_half_size_m = round12(shape.core_half_size_m / r);
  s.unit_criteria.facet_angle_deg = c.facet_angle_deg;
  s.unit_criteria.facet_distance_m = round12(c.facet_distance_m / r);
  s.unit_criteria.facet_size_m = round12(c.facet_size_m / r);
  if (shape.geometry == sim::Geometry::sphere) {
    // On the unit sphere a surface Delaunay ball of radius rho (centred on the sphere, with the
    // facet's vertices on its boundary and on the sphere) meets the sphere in a circle whose
    // plane lies rho^2 / 2 below the ball's centre; that circle is the facet's circumcircle, so
    // CGAL's facet_distance (circumcentre to ball centre) is exactly rho^2 / 2. The distance
    // bound d thus fails exactly when rho > sqrt(2 d), and a size bound s >= sqrt(2 d) can never
    // fail alone: the meshes it accepts are those the distance bound accepts (only the order in
    // which CGAL refines, by the first failing criterion, may differ). Such a redundant bound is
    // replaced by 2, also redundant
    // (an empty ball of radius 2 centred on the unit sphere cannot exist), so that every sphere
    // whose size bound is redundant has the same canonical form.
    if (s.unit_criteria.facet_size_m >= std::sqrt(2 * s.unit_criteria.facet_distance_m))
      s.unit_criteria.facet_size_m = 2;
  }
  return s;
}

}  // namespace thaw::mesh
